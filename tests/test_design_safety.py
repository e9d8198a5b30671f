"""The design search against hostile files and peers (issue 29): a planted pickle never runs, a
planted link is never written through, checkpoints are checked before use, temporaries of
interrupted or killed runs do not stay, a scheduler that never answers (or answers garbage)
cannot hang the search, and study values are refused at load, located."""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import os
import pickle
import random
import signal
import socket
import subprocess
import sys
import threading
import time
import zipfile

import numpy as np
import pytest

import linkage

design = pytest.importorskip("linkage.design")
from linkage.design import checkpoint as ckpt  # noqa: E402
from linkage.design import cluster  # noqa: E402

search_mod = sys.modules["linkage.design.search"]  # the module: the package exports search()


def small(**kw):
    base = design.Study(
        family="fourbar",
        objectives=("stride", "straightness", "speed_variation"),
        population=8,
        budget=8 * 4,
        seed=7,
        settings=design.Settings(samples=64, foot_bar=100.0),
        constraints=design.Constraints(min_duty=0.0),
        chunk=4,
        name="small",
    )
    return dataclasses.replace(base, **kw)


def cli(*args, timeout=120):
    return subprocess.run(
        [sys.executable, "-m", "linkage", *map(str, args)],
        capture_output=True,
        text=True,
        timeout=timeout,
    )


def dead_pid():
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


STUDY = "[design]\npopulation = 8\nbudget = 32\nsamples = 64\nfoot_bar = 100.0\nchoose = 0\n"


# -- 1. no code from a data file ----------------------------------------------------------


class _Payload:
    def __init__(self, marker):
        self.marker = str(marker)

    def __reduce__(self):
        return (open, (self.marker, "w"))


def test_planted_pickle_checkpoint_never_runs_its_code(tmp_path):
    ck, marker = tmp_path / "run.checkpoint", tmp_path / "PWNED"
    ck.write_bytes(pickle.dumps({"magic": "linkage-design-checkpoint-1", "x": _Payload(marker)}))
    before = ck.read_bytes()
    with pytest.raises(linkage.LinkageError, match=r"run\.checkpoint.*earlier linkage release"):
        design.search(small(), checkpoint=ck)
    assert not marker.exists(), "the pickle's payload ran"
    assert ck.read_bytes() == before
    # The documented command with the default checkpoint beside the report.
    study = tmp_path / "s.toml"
    study.write_text(STUDY)
    (tmp_path / ".rep.checkpoint").write_bytes(before)
    r = cli("design", study, "--out", tmp_path / "rep", "--quiet")
    assert r.returncode == 2, r.stderr
    assert ".rep.checkpoint" in r.stderr and "Traceback" not in r.stderr
    assert not marker.exists() and not (tmp_path / "rep").exists()


def test_checkpoint_is_plain_arrays_and_resumes_to_the_same_front(tmp_path):
    whole = design.search(small())
    for stop in (1, 3):
        ck = tmp_path / f"c{stop}"
        design.search(small(), checkpoint=ck, stop_after=stop)
        assert ck.read_bytes()[:2] == b"PK"  # a zip of .npy arrays
        with zipfile.ZipFile(ck) as z:
            assert sorted(z.namelist()) == sorted(f"{k}.npy" for k in ckpt._MEMBERS)
        got = design.search(small(), checkpoint=ck)
        np.testing.assert_array_equal(got.x, whole.x)
        np.testing.assert_array_equal(got.figures, whole.figures)
        np.testing.assert_array_equal(got.front, whole.front)
    # Stopped and resumed after every generation.
    ck = tmp_path / "each"
    for gen in range(1, small().generations + 1):
        got = design.search(small(), checkpoint=ck, stop_after=1)
        assert got.generations == gen
    np.testing.assert_array_equal(got.x, whole.x)
    np.testing.assert_array_equal(got.front, whole.front)


def test_global_random_states_round_trip(tmp_path, monkeypatch):
    """For pymoo releases that draw from the process-wide generators (_uses_global_rng)."""
    monkeypatch.setattr(search_mod, "_uses_global_rng", lambda algorithm: True)
    ck = tmp_path / "c"
    design.search(small(), checkpoint=ck, stop_after=2)
    want = (random.getstate(), np.random.get_state(legacy=True))  # noqa: NPY002
    random.seed(99)
    np.random.seed(99)  # noqa: NPY002
    design.search(small(), checkpoint=ck, stop_after=0)
    got = np.random.get_state(legacy=True)  # noqa: NPY002
    assert random.getstate() == want[0]
    assert got[0] == want[1][0] and np.array_equal(got[1], want[1][1]) and got[2:] == want[1][2:]


# -- the tampered checkpoint corpus -------------------------------------------------------


def _arrays(path):
    with np.load(path, allow_pickle=False) as z:
        return {k: np.array(z[k]) for k in z.files}


def _write(path, arrays, compressed=False):
    buf = io.BytesIO()
    (np.savez_compressed if compressed else np.savez)(buf, **arrays)
    path.write_bytes(buf.getvalue())


def _meta(arrays, **change):
    meta = json.loads(arrays["meta"].tobytes())
    meta.update(change)
    return {**arrays, "meta": np.frombuffer(json.dumps(meta).encode(), dtype="u1")}


def _huge_header(path):
    """An x member whose header claims 10**12 rows over a few bytes of data."""
    good = _arrays(path)
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w", zipfile.ZIP_STORED) as z:
        for k, v in good.items():
            raw = io.BytesIO()
            np.save(raw, v)
            data = raw.getvalue()
            if k == "x":
                head = {"descr": "<f8", "fortran_order": False, "shape": (10**12, 6)}
                raw = io.BytesIO()
                np.lib.format.write_array_header_1_0(raw, head)
                data = raw.getvalue() + v.tobytes()
            z.writestr(f"{k}.npy", data)
    path.write_bytes(buf.getvalue())


TAMPER = {
    "empty": (lambda p, a: p.write_bytes(b""), "not a linkage design checkpoint"),
    "random bytes": (lambda p, a: p.write_bytes(os.urandom(4000)), "not a linkage design"),
    "truncated": (lambda p, a: p.write_bytes(p.read_bytes()[:-100]), "not a linkage design"),
    "json text": (lambda p, a: p.write_text('{"magic": 1}'), "not a linkage design"),
    "compressed": (lambda p, a: _write(p, a, compressed=True), "compressed"),
    "extra member": (lambda p, a: _write(p, {**a, "more": np.zeros(3)}), "members"),
    "object array": (
        lambda p, a: _write(p, {**a, "pop_rank": np.array([{"x": 1}] * 8, dtype=object)}),
        "pop_rank",
    ),
    "huge header": (lambda p, a: _huge_header(p), "does not fit"),
    "x as int": (lambda p, a: _write(p, {**a, "x": a["x"].astype("<i8")}), "not 2-D"),
    "no magic": (lambda p, a: _write(p, _meta(a, magic="other")), "not a linkage design"),
    "other version": (lambda p, a: _write(p, _meta(a, version=1)), "another linkage release"),
    "other study": (lambda p, a: _write(p, _meta(a, fingerprint="0" * 16)), "different study"),
    "generation 0": (lambda p, a: _write(p, _meta(a, generation=0)), "generation"),
    "generation huge": (lambda p, a: _write(p, _meta(a, generation=10**30)), "generation"),
    "generation text": (lambda p, a: _write(p, _meta(a, generation="2")), "generation"),
    "rng garbage": (lambda p, a: _write(p, _meta(a, rng={"bit_generator": "PCG64"})), "random"),
    "rng list": (lambda p, a: _write(p, _meta(a, rng=[1, 2])), "rng"),
    "meta deep": (
        lambda p, a: _write(
            p, {**a, "meta": np.frombuffer(("[" * 5000 + "]" * 5000).encode(), dtype="u1")}
        ),
        "deep",
    ),
    "x NaN": (lambda p, a: _write(p, {**a, "x": np.where(a["x"] > 0, np.nan, a["x"])}), "bounds"),
    "x out of box": (lambda p, a: _write(p, {**a, "x": a["x"] * 1e6}), "bounds"),
    "figures short": (lambda p, a: _write(p, {**a, "figures": a["figures"][:, :3]}), "figures"),
    "pop index": (lambda p, a: _write(p, {**a, "pop_index": a["pop_index"] + 10**6}), "survivor"),
    "pop sizes": (lambda p, a: _write(p, {**a, "pop_rank": a["pop_rank"][:2]}), "population"),
    "rank": (lambda p, a: _write(p, {**a, "pop_rank": a["pop_rank"] - 5}), "rank"),
    "crowding": (
        lambda p, a: _write(p, {**a, "pop_crowding": -np.abs(a["pop_crowding"]) - 1}),
        "crowding",
    ),
    "born later": (lambda p, a: _write(p, {**a, "pop_gen": a["pop_gen"] + 50}), "born"),
}


@pytest.mark.parametrize("name", list(TAMPER))
def test_tampered_checkpoints_are_refused_naming_the_file(tmp_path, name):
    ck = tmp_path / "run.checkpoint"
    design.search(small(), checkpoint=ck, stop_after=2)
    tamper, words = TAMPER[name]
    tamper(ck, _arrays(ck))
    before = ck.read_bytes()
    with pytest.raises(linkage.LinkageError) as e:
        design.search(small(), checkpoint=ck)
    msg = str(e.value)
    assert str(ck) in msg and words in msg, msg
    assert ck.read_bytes() == before  # never overwritten


def test_checkpoint_larger_than_any_of_the_study_is_refused_unread(tmp_path):
    ck = tmp_path / "run.checkpoint"
    with open(ck, "wb") as fh:
        fh.truncate(ckpt.size_limit(small()) + 1)
    with pytest.raises(linkage.LinkageError, match="more than the"):
        design.search(small(), checkpoint=ck)


def test_checkpoint_that_is_a_folder_a_fifo_or_a_link_to_a_device_is_refused(tmp_path):
    ck = tmp_path / "run.checkpoint"
    ck.mkdir()
    with pytest.raises(linkage.LinkageError, match="folder"):
        design.search(small(), checkpoint=ck)
    fifo = tmp_path / "fifo.checkpoint"
    os.mkfifo(fifo)
    with pytest.raises(linkage.LinkageError, match="pipe"):
        design.search(small(), checkpoint=fifo)
    zero = tmp_path / "zero.checkpoint"
    os.symlink("/dev/zero", zero)
    with pytest.raises(linkage.LinkageError, match="symbolic link"):
        design.search(small(), checkpoint=zero)


# -- 2. no writes through planted links ---------------------------------------------------


def test_planted_links_at_the_checkpoint_temporaries_leave_the_victim_alone(tmp_path):
    victim = tmp_path / "thesis.tex"
    victim.write_bytes(b"\\chapter{mine}\n")
    ck = tmp_path / ".rep.checkpoint"
    # Every name the old code wrote its temporary to, for this process.
    os.symlink(victim, tmp_path / f".{ck.name}.partial-{os.getpid()}")
    for k in range(5):
        os.symlink(victim, tmp_path / f".{ck.name}.{os.getpid()}.planted{k}.tmp")
    design.search(small(), checkpoint=ck)
    assert victim.read_bytes() == b"\\chapter{mine}\n"
    assert ck.is_file() and not ck.is_symlink()


@pytest.mark.parametrize("dangling", [False, True])
def test_a_link_at_the_checkpoint_itself_is_refused(tmp_path, dangling):
    victim = tmp_path / "thesis.tex"
    if not dangling:
        victim.write_bytes(b"mine")
    ck = tmp_path / ".rep.checkpoint"
    os.symlink(victim, ck)
    with pytest.raises(linkage.LinkageError, match="symbolic link"):
        design.search(small(), checkpoint=ck)
    assert (victim.read_bytes() == b"mine") if not dangling else not victim.exists()
    assert ck.is_symlink()


# -- 6. temporaries of interrupted and killed runs ----------------------------------------


def test_interrupted_checkpoint_write_leaves_no_temporary_and_says_what_is_kept(
    tmp_path, monkeypatch, capsys
):
    study = tmp_path / "s.toml"
    study.write_text(STUDY)
    calls = []
    fsync = os.fsync

    def interrupted(fd):
        calls.append(fd)
        if len(calls) == 2:  # the second checkpoint, half written
            raise KeyboardInterrupt
        fsync(fd)

    monkeypatch.setattr(os, "fsync", interrupted)
    with pytest.raises(KeyboardInterrupt):
        design.main_design(str(study), str(tmp_path / "rep"), False, None, quiet=True)
    assert sorted(os.listdir(tmp_path)) == [".rep.checkpoint", "s.toml"]
    assert "the search so far is kept in" in capsys.readouterr().err


def test_ctrl_c_while_the_report_is_written_says_the_search_is_kept(tmp_path, monkeypatch, capsys):
    """The search is done and in the checkpoint: the note says so (a hostile re-trial saw a stop
    here end with no word of the checkpoint)."""
    from linkage.design import report as design_report

    study = tmp_path / "s.toml"
    study.write_text(STUDY)

    def stopped(*_a, **_k):
        raise KeyboardInterrupt

    monkeypatch.setattr(design_report, "write_report", stopped)
    with pytest.raises(KeyboardInterrupt):
        design.main_design(str(study), str(tmp_path / "rep"), False, None, quiet=True)
    assert sorted(os.listdir(tmp_path)) == [".rep.checkpoint", "s.toml"]
    assert "the search so far is kept in" in capsys.readouterr().err


def test_ctrl_c_during_the_cli_search(tmp_path):
    study = tmp_path / "s.toml"
    study.write_text(STUDY.replace("budget = 32", "budget = 4000"))
    out = tmp_path / "rep"
    p = subprocess.Popen(
        [sys.executable, "-m", "linkage", "design", str(study), "--out", str(out), "--quiet"],
        stderr=subprocess.PIPE,
        text=True,
    )
    ck = tmp_path / ".rep.checkpoint"
    for _ in range(3000):
        if ck.exists() or p.poll() is not None:
            break
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130, err
    assert sorted(os.listdir(tmp_path)) == [".rep.checkpoint", "s.toml"], err
    assert "kept in" in err and "Traceback" not in err
    # The closing line does not contradict the kept checkpoint.
    assert "nothing was written" not in err and "no report was written" in err, err


def test_stale_checkpoint_temporaries_of_dead_runs_are_swept(tmp_path):
    ck = tmp_path / ".rep.checkpoint"
    gone = dead_pid()
    stale = [f".{ck.name}.{gone}.abc_123.tmp", f".{ck.name}.partial-{gone}"]
    live = f".{ck.name}.{os.getpid()}.xyz.tmp"
    link = f".{ck.name}.{gone}.link.tmp"
    for name in [*stale, live]:
        (tmp_path / name).write_bytes(b"half a checkpoint")
    other = tmp_path / "notes.txt"
    other.write_text("mine")
    os.symlink(other, tmp_path / link)
    design.search(small(), checkpoint=ck, stop_after=1)
    left = set(os.listdir(tmp_path))
    assert not left & set(stale)
    assert {live, link, "notes.txt", ck.name} <= left
    assert other.read_text() == "mine"


# -- 4. schedulers that never answer, or answer garbage -----------------------------------


@contextlib.contextmanager
def hostile_server(mode):
    """A TCP server on 127.0.0.1 that accepts and then says nothing, or sends random bytes."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(16)
    srv.settimeout(0.2)
    stop = threading.Event()
    conns = []

    def serve():
        while not stop.is_set():
            try:
                c, _ = srv.accept()
            except OSError:
                continue
            conns.append(c)
            if mode == "random":
                with contextlib.suppress(OSError):
                    rng = np.random.default_rng(len(conns))
                    for _ in range(20):
                        c.sendall(rng.bytes(4096))

    t = threading.Thread(target=serve, daemon=True)
    t.start()
    try:
        yield f"tcp://127.0.0.1:{srv.getsockname()[1]}"
    finally:
        stop.set()
        t.join(5)
        for c in conns:
            c.close()
        srv.close()


def test_silent_scheduler_fails_within_a_minute_naming_address_and_study(tmp_path):
    with hostile_server("silent") as address:
        study = tmp_path / "s.toml"
        study.write_text(STUDY + f'scheduler = "{address}"\n')
        t0 = time.monotonic()
        r = cli("design", study, "--out", tmp_path / "rep", "--quiet", timeout=90)
        took = time.monotonic() - t0
    assert took < 60, took
    assert r.returncode == 2, r.stderr
    assert f"{study}:7: [design] scheduler" in r.stderr and address in r.stderr, r.stderr
    assert "no answer within" in r.stderr and "internal error" not in r.stderr
    assert not (tmp_path / "rep").exists()


def test_scheduler_sending_random_bytes_is_a_clear_error(tmp_path):
    with hostile_server("random") as address:
        t0 = time.monotonic()
        with pytest.raises(linkage.LinkageError, match="did not answer as a Dask scheduler"):
            design.search(small(scheduler=address))
        assert time.monotonic() - t0 < 60


def test_scheduler_without_workers_does_not_wait_forever(monkeypatch):
    import distributed

    monkeypatch.setattr(cluster, "POLL", 0.5)
    monkeypatch.setattr(cluster, "NO_WORKERS_TIMEOUT", 2.0)
    with distributed.LocalCluster(n_workers=0, dashboard_address=None) as lc:
        t0 = time.monotonic()
        with pytest.raises(cluster.SchedulerError, match="no worker"):
            design.search(small(scheduler=lc.scheduler_address))
        assert time.monotonic() - t0 < 60


# -- 5. study values refused at load, located ---------------------------------------------


@pytest.mark.parametrize(
    "line, key, words",
    [
        ('scheduler = "garbage"', "scheduler", "not an address"),
        ('scheduler = "http://10.0.0.5:8787"', "scheduler", "web address"),
        ('scheduler = "inproc://10.0.0.5/1/2"', "scheduler", "same process"),
        ('scheduler = "tls://10.0.0.5:8786"', "scheduler", "certificates"),
        ('scheduler = "ucx://10.0.0.5:8786"', "scheduler", "not supported"),
        ('scheduler = "tcp://10.0.0.5\\u0000:8786"', "scheduler", "control character"),
        ('scheduler = ""', "scheduler", "empty"),
        ('scheduler = "tcp://10.0.0.5:99999"', "scheduler", "port"),
        ('objectives = [["stride"]]', "objectives", "list of names"),
        ('objectives = ["stride", "stride"]', "objectives", "twice"),
        ("stance_tol = 1e300", "stance_tol", "from 0 to 0.5"),
        ("stance_tol = 0.9", "stance_tol", "from 0 to 0.5"),
        ("foot_bar = 1e300", "foot_bar", "length"),
        ("population = 1000000", "population", "TiB"),
        ("budget = 1000000000000", "budget", "candidates need"),
    ],
)
def test_bad_study_values_are_refused_at_load_located(tmp_path, line, key, words):
    p = tmp_path / "bad.toml"
    p.write_text(f"[design]\nsamples = 64\n{line}\n")
    with pytest.raises(linkage.LinkageError) as e:
        design.load_study(p)
    msg = str(e.value)
    assert msg.startswith(f"{p}:3: [design] {key}:") and words in msg, msg


@pytest.mark.parametrize("depth", [600, 50_000])
def test_a_study_nested_deeper_than_a_scene_may_be_is_refused_located(tmp_path, depth):
    """Brackets nested 600 deep overflowed the TOML parser's recursion (RecursionError, exit 3);
    scenes had refused them, studies did not (found by a hostile re-trial)."""
    p = tmp_path / "deep.toml"
    p.write_text(f"[design.bounds]\ncoupler = {'[' * depth}1{']' * depth}\n")
    with pytest.raises(linkage.LinkageError) as e:
        design.load_study(p)
    assert str(e.value) == f"{p}:2: not a study: brackets nested more than 32 deep"


@pytest.mark.parametrize(
    "section, line, key, words",
    [
        ("bounds", "coupler = [-5.0, 30.0]", "coupler", "a length: more than 0"),
        ("bounds", "ground = [0.0, 30.0]", "ground", "a length"),
        ("bounds", "ground_angle = [-10.0, 10.0]", "ground_angle", "radians"),
        ("bounds", "along = [-1e300, 10.0]", "along", "offset"),
        ("constraints", "min_duty = 1.5", "min_duty", "fraction"),
        ("constraints", "min_transmission = 120.0", "min_transmission", "degrees"),
        ("constraints", "min_lift = 1e300", "min_lift", "length"),
    ],
)
def test_bounds_and_constraints_out_of_the_domain_are_located(tmp_path, section, line, key, words):
    p = tmp_path / "bad.toml"
    p.write_text(f"[design]\nsamples = 64\n[design.{section}]\n{line}\n")
    with pytest.raises(linkage.LinkageError) as e:
        design.load_study(p)
    msg = str(e.value)
    assert msg.startswith(f"{p}:4: [design.{section}] {key}:") and words in msg, msg


def test_jansen_and_klann_domains(tmp_path):
    p = tmp_path / "j.toml"
    p.write_text('[design]\nfamily = "jansen"\n[design.bounds]\nb = [-41.5, 41.5]\n')
    with pytest.raises(linkage.LinkageError, match=r"j\.toml:4: \[design.bounds\] b: .*length"):
        design.load_study(p)
    p.write_text('[design]\nfamily = "klann"\n[design.bounds]\ntilt = [-400.0, 30.0]\n')
    with pytest.raises(linkage.LinkageError, match=r":4: \[design.bounds\] tilt: .*degrees"):
        design.load_study(p)
    # Jansen's frame offsets a and l may take either sign.
    p.write_text('[design]\nfamily = "jansen"\n[design.bounds]\nl = [-7.8, 7.8]\n')
    assert design.load_study(p).study.bounds["l"] == (-7.8, 7.8)


def test_cli_exit_2_not_internal_error_for_nested_objectives(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text('[design]\nobjectives = [["stride"]]\n')
    r = cli("design", p, "--quiet")
    assert r.returncode == 2 and f"{p}:2: [design] objectives" in r.stderr, r.stderr


def test_population_memory_is_a_memory_error_too():
    with pytest.raises(MemoryError, match="TiB"):
        design.Study(population=10**6, budget=10**6)
    with pytest.raises(linkage.LinkageError, match="scheduler"):
        design.Study(scheduler="garbage")


def test_scheduler_addresses_normalised():
    assert cluster.scheduler_address("10.0.0.5:8786") == "tcp://10.0.0.5:8786"
    assert cluster.scheduler_address("tcp://node-1.example.org:1") == "tcp://node-1.example.org:1"
    assert cluster.scheduler_address("tcp://[::1]:8786") == "tcp://[::1]:8786"
    for bad in ("tcp://", "tcp://:8786", "tcp://host", "tcp://[zz]:1", "tcp://a b:1", "x://a:1"):
        with pytest.raises(linkage.LinkageError):
            cluster.scheduler_address(bad)
