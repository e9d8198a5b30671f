"""The `linkage catalog` table (catalog.table): error estimates from a second resolution and a
cache in the user's cache folder that is keyed, confined to that folder and robust to
corruption."""

import json

import pytest

from linkage import catalog


@pytest.fixture
def cache(tmp_path, monkeypatch):
    folder = tmp_path / "cache"
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(folder))
    return folder


def test_table_estimates_errors_from_a_second_resolution(cache):
    rows = catalog.table(samples=1001, cache=False)
    assert not cache.exists()  # cache=False writes nothing
    fine = catalog.figures(samples=1001)
    coarse = catalog.figures(samples=catalog.check_count(1001))
    for r, f, c in zip(rows, fine, coarse):
        assert r.name == f.name and r.straight_length == f.straight_length
        assert r.straight_length_error == abs(f.straight_length - c.straight_length)
        assert r.samples == 1001


def test_the_error_covers_the_difference_from_twice_the_samples_for_four_bars(cache):
    rows = {r.name: r for r in catalog.table(cache=False)}
    ref = {r.name: r for r in catalog.figures(samples=8001)}
    for name in catalog.FOUR_BARS:
        r = rows[name]
        assert (
            abs(r.straight_length - ref[name].straight_length) <= 2 * r.straight_length_error + 0.02
        )


def test_the_cache_is_written_once_read_back_and_keyed_by_the_parameters(cache):
    first = catalog.table(samples=801)
    files = list(cache.iterdir())
    assert len(files) == 1 and files[0].name.startswith("catalog-")
    assert catalog.table(samples=801) == first
    catalog.table(rel_tol=2e-3, samples=801)
    assert len(list(cache.iterdir())) == 2
    # Only the cache folder is written, nothing else beside it.
    assert {p.name for p in cache.parent.iterdir()} == {"cache"}


@pytest.mark.parametrize("junk", ["{not json", "[]", '[{"name": "watt"}]', "\x00\xff", '"x"'])
def test_a_corrupt_cache_is_ignored_and_rewritten(cache, junk):
    good = catalog.table(samples=801)
    (path,) = cache.iterdir()
    path.write_bytes(junk.encode("utf-8", "surrogateescape") if isinstance(junk, str) else junk)
    assert catalog.table(samples=801) == good
    assert json.loads(path.read_text())[0]["name"] == "watt"


def test_an_unwritable_cache_folder_still_gives_the_table(tmp_path, monkeypatch):
    blocker = tmp_path / "file"
    blocker.write_text("not a folder")
    monkeypatch.setenv("LINKAGE_CACHE_DIR", str(blocker / "sub"))
    rows = catalog.table(samples=801)
    assert [r.name for r in rows] == list(catalog.names())
    assert blocker.read_text() == "not a folder"


def test_format_table_prints_the_errors(cache):
    lines = catalog.format_table(catalog.table(samples=801, cache=False), 1e-3)
    assert "801 samples per circuit" in lines[0]
    hoecken = next(line for line in lines if line.startswith("hoecken "))
    assert "±" in hoecken and "crank-rocker" in hoecken
