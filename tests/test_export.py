"""The data and CAD export (linkage.export): summary.json typed, CSV with units, DXF read back with
ezdxf, SVG parsed with xml.etree — every coordinate compared with the run's own sweep."""

import csv
import json
import math
import xml.etree.ElementTree as ET
from pathlib import Path

import ezdxf
import numpy as np
import pytest

from linkage import LinkageError, export, figures, runner, scene

ROOT = Path(__file__).resolve().parents[1]
SVG = "{http://www.w3.org/2000/svg}"


def run(name, samples=181):
    return runner.run(scene.parse((ROOT / "examples" / f"{name}.toml").read_text()), samples)


@pytest.fixture(scope="module")
def hoecken(tmp_path_factory):
    res = run("hoecken")
    out = tmp_path_factory.mktemp("hoecken")
    files = export.write_data(res, out)
    return res, out, files


@pytest.fixture(scope="module")
def quadruped(tmp_path_factory):
    res = run("quadruped_hoecken")
    out = tmp_path_factory.mktemp("quadruped")
    files = export.write_data(res, out)
    return res, out, files


def test_write_data_writes_every_file_and_the_summary_lists_them(hoecken):
    _res, out, files = hoecken
    names = {f.name for f in files}
    assert names == {"mechanism.dxf", "mechanism.svg", "data.npz", "data.csv", "summary.json"}
    summary = json.loads((out / "summary.json").read_text())
    assert set(summary["files"]) == {p.name for p in out.iterdir()}


def test_summary_numbers_are_typed_with_units_and_errors(hoecken):
    res, out, _ = hoecken
    summary = json.loads((out / "summary.json").read_text())
    assert summary["schema"] == export.SCHEMA
    assert summary["scene"] == res.scene.name and summary["units"] == "mm"
    assert summary["samples"] == 181 and summary["check_samples"] == list(res.check_samples)
    figs = {f["figure"]: f for f in summary["figures"]}
    assert len(figs) == len(res.figures)
    for f in summary["figures"]:
        assert set(f) == {"figure", "value", "text", "unit", "error", "error_note", "exact"}
        assert f["error"] is None or (isinstance(f["error"], (float, int)) and f["error"] >= 0)
    straight = figs["straight part within 0.1 % of size"]
    assert isinstance(straight["value"], float) and straight["unit"] == "mm"
    assert isinstance(straight["error"], float)
    row = {r[0]: r for r in res.figures}["straight part within 0.1 % of size"]
    assert straight["value"] == res.straight.length == row.value
    rng = figs["trace x range"]["value"]
    assert rng == [float(np.nanmin(res.sweep.point[:, 0])), float(np.nanmax(res.sweep.point[:, 0]))]
    assert figs["samples assembled"]["value"] == 181 and figs["samples assembled"]["exact"]
    assert figs["Grashof class"]["value"] == "crank-rocker"
    # No number is stored as a string: every value is a number, a list of numbers, a word or null.
    for f in summary["figures"]:
        v = f["value"]
        if isinstance(v, str):
            with pytest.raises(ValueError):
                float(v)
    assert all(isinstance(v, float) for v in summary["stages_s"].values())
    assert summary["pose"]["sample"] == 0


def test_an_infinite_radius_is_null_in_json_and_spelled_out(tmp_path):
    res = runner.run(
        scene.parse(
            'name = "p"\nunits = "mm"\noutputs = ["trajectory", "curvature"]\n'
            '[mechanism]\ncatalog = "peaucellier"\n[drive]\nkind = "constant"\nomega = 1.0\n'
        ),
        181,
    )
    row = {r[0]: r for r in res.figures}["smallest radius of curvature"]
    assert row[1].startswith("∞") and row.value is None
    export.write_data(res, tmp_path)
    text = (tmp_path / "summary.json").read_text()
    assert "NaN" not in text and "Infinity" not in text
    figs = {f["figure"]: f for f in json.loads(text)["figures"]}
    assert figs["smallest radius of curvature"]["value"] is None


def test_csv_headers_carry_units_and_hold_the_trace_and_joints(hoecken):
    res, out, _ = hoecken
    with open(out / "data.csv", newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        rows = [list(map(float, r)) for r in reader]
    assert header[:4] == ["time [s]", "theta [rad]", "omega [rad/s]", "alpha [rad/s²]"]
    assert "trace_x [mm]" in header and "joint_B_y [mm]" in header
    assert "velocity_x [mm/s]" in header and "curvature [1/mm]" in header
    assert all("[" in h for h in header)
    data = np.array(rows)
    assert data.shape == (181, len(header))
    np.testing.assert_array_equal(data[:, header.index("trace_x [mm]")], res.sweep.point[:, 0])
    b = res.sweep.joint_names.index("B")
    np.testing.assert_array_equal(
        data[:, header.index("joint_B_y [mm]")], res.sweep.joints[:, b, 1]
    )


def test_walker_csv_holds_every_foot_in_3d_and_stance_flags(quadruped):
    res, out, _ = quadruped
    with open(out / "data.csv", newline="") as fh:
        reader = csv.reader(fh)
        header = next(reader)
        data = np.array([list(map(float, r)) for r in reader])
    sim = res.simulation
    for i, leg in enumerate(sim.legs):
        for c, axis in enumerate("xyz"):
            col = header.index(f"foot_{leg}_{axis} [mm]")
            np.testing.assert_array_equal(data[:, col], sim.feet[:, i, c])
        col = header.index(f"stance_{leg} [1 = down]")
        np.testing.assert_array_equal(data[:, col], sim.stance[:, i].astype(float))
    assert "stability_margin [mm]" in header and "body_position [mm]" in header
    npz = np.load(out / "data.npz")
    np.testing.assert_array_equal(npz["feet"], sim.feet)


def test_csv_of_a_scene_without_units_says_length_units(tmp_path):
    res = run("jansen")
    export.write_data(res, tmp_path, cad=False)
    header = (tmp_path / "data.csv").read_text().splitlines()[0].split(",")
    assert "trace_x [length units]" in header
    assert not (tmp_path / "mechanism.dxf").exists()


def test_dxf_reads_back_with_layers_units_links_and_the_full_path(hoecken):
    res, out, _ = hoecken
    doc = ezdxf.readfile(out / "mechanism.dxf")
    assert doc.header["$INSUNITS"] == 4  # mm
    layers = {layer.dxf.name for layer in doc.layers}
    assert {"LINKS", "PIVOTS", "GROUND", "JOINTS", "PATH_trace_P"} <= layers
    msp = doc.modelspace()
    links = msp.query('LWPOLYLINE[layer=="LINKS"]')
    mech = res.mechanism.mechanism()
    assert len(links) == len(mech.links) - 1  # every moving link, not the ground
    # The links at the pose (sample 0) join the joints the mechanism says they join.
    names = res.sweep.joint_names
    j0 = res.sweep.joints[0]
    drawn = sorted(sorted(tuple(np.round(p, 9)) for p in e.get_points("xy")) for e in links)
    want = sorted(
        sorted(tuple(np.round(j0[names.index(n)], 9)) for n in ms) for ms in mech.link_members()[1:]
    )
    assert drawn == want
    (path,) = msp.query('LWPOLYLINE[layer=="PATH_trace_P"]')
    pts = np.array(list(path.get_points("xy")))
    assert pts.shape == (181, 2)
    np.testing.assert_allclose(pts, res.sweep.point, rtol=0, atol=1e-12)
    pivots = msp.query('CIRCLE[layer=="PIVOTS"]')
    centres = sorted((round(c.dxf.center.x, 9), round(c.dxf.center.y, 9)) for c in pivots)
    assert centres == sorted([(0.0, 0.0), (20.0, 0.0)])  # O and C


def test_dxf_of_a_metres_walker_has_one_layer_per_leg_and_path(tmp_path):
    res = run("hexapod_tripod")
    export.write_data(res, tmp_path)
    doc = ezdxf.readfile(tmp_path / "mechanism.dxf")
    assert doc.header["$INSUNITS"] == 6  # m
    layers = {layer.dxf.name for layer in doc.layers}
    legs = res.simulation.legs
    assert {f"LEG_{leg}" for leg in legs} <= layers
    msp = doc.modelspace()
    for i, label in enumerate(res.walker.leg_labels()):
        polys = msp.query(f'LWPOLYLINE[layer=="PATH_{label}"]')
        pts = np.concatenate([np.array(list(p.get_points("xy"))) for p in polys])
        assert len(pts) == len(res.time)
        # The hexapod's legs work in the horizontal plane: drawn from above (x, y).
        np.testing.assert_allclose(pts, res.simulation.feet[:, i][:, [0, 1]], atol=1e-15)
    assert len(msp.query('LWPOLYLINE[layer=="BODY"]')) == 1


def test_a_path_with_unassembled_samples_is_split_at_the_gaps(tmp_path):
    res = run("watt", samples=361)
    export.write_data(res, tmp_path)
    doc = ezdxf.readfile(tmp_path / "mechanism.dxf")
    polys = doc.modelspace().query('LWPOLYLINE[layer=="PATH_trace_P"]')
    total = sum(len(list(p.get_points("xy"))) for p in polys)
    ok = res.sweep.valid
    assert total == int(ok.sum()) and len(polys) >= 1
    for p in polys:
        pts = np.array(list(p.get_points("xy")))
        assert np.isfinite(pts).all()
    # The pose is the first assembled sample.
    summary = json.loads((tmp_path / "summary.json").read_text())
    assert summary["pose"]["sample"] == int(np.argmax(ok))


def test_svg_parses_with_named_layers_in_scene_coordinates(hoecken):
    res, out, _ = hoecken
    root = ET.parse(out / "mechanism.svg").getroot()
    assert root.tag == f"{SVG}svg" and root.get("width").endswith("mm")
    groups = {g.get("data-layer"): g for g in root.iter(f"{SVG}g") if g.get("data-layer")}
    assert {"LINKS", "PIVOTS", "GROUND", "JOINTS", "PATH_trace_P"} <= set(groups)
    assert len(groups["LINKS"].findall(f"{SVG}polyline")) == 3
    (path,) = groups["PATH_trace_P"].findall(f"{SVG}polyline")
    pts = np.array([list(map(float, p.split(","))) for p in path.get("points").split()])
    np.testing.assert_allclose(pts, res.sweep.point, rtol=1e-9)


def test_pose_is_chosen_checked_and_recorded(tmp_path):
    res = run("hoecken")
    _files, k = export.write_cad(res, tmp_path, pose=45)
    assert k == 45
    doc = ezdxf.readfile(tmp_path / "mechanism.dxf")
    names = res.sweep.joint_names
    a = res.sweep.joints[45, names.index("A")]
    ends = [
        pt
        for e in doc.modelspace().query('LWPOLYLINE[layer=="LINKS"]')
        for pt in e.get_points("xy")
    ]
    assert any(math.dist(p, a) < 1e-9 for p in ends)
    with pytest.raises(LinkageError, match="not a sample"):
        export.write_cad(res, tmp_path, pose=10_000)
    with pytest.raises(TypeError):
        export.write_cad(res, tmp_path, pose=1.5)
    watt = run("watt", samples=361)
    bad = int(np.argmin(watt.sweep.valid))
    with pytest.raises(LinkageError, match="does not assemble"):
        export.write_cad(watt, tmp_path, pose=bad)


def test_the_synthesis_exports_refuse_a_run_that_is_not_one(hoecken, tmp_path):
    # candidate_rows asserted (an AssertionError, or an AttributeError under python -O).
    res, _out, _files = hoecken
    for call in (
        lambda: export.candidate_rows(res),
        lambda: export.write_candidates_csv(res, tmp_path / "candidates.csv"),
        lambda: export.write_synthesis(res, tmp_path),
        lambda: export.synthesis_drawing(res),
    ):
        with pytest.raises(LinkageError, match="not a synthesis run"):
            call()
    assert not (tmp_path / "candidates.csv").exists()


def test_layer_names_are_valid_dxf_names():
    assert export.layer_name('PATH_a/b:c "d"') == "PATH_a_b_c_d"
    assert export.layer_name("///") == "_"


def test_a_slider_crank_draws_its_block_on_its_guide(tmp_path):
    import linkage
    from linkage.scene import Scene

    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("G", (0, -5))
    m.crank("A", "O", radius=10)
    m.slider("B", "A", 30, "G", direction=(1, 0))
    theta = np.linspace(0, 2 * np.pi, 73)
    s = m.sweep(theta)
    res = figures.Result(
        scene=Scene(name="slider", path=None, outputs=("trajectory",), units="mm"),
        time=theta,
        theta=theta,
        sweep=s,
        mechanism=m,
    )
    res.arrays.update(time=theta, theta=theta, point=s.point, joints=s.joints)
    export.write_data(res, tmp_path)
    msp = ezdxf.readfile(tmp_path / "mechanism.dxf").modelspace()
    assert len(msp.query('LWPOLYLINE[layer=="LINKS"]')) == 2  # crank O-A, rod A-B
    block, guide = sorted(msp.query('LWPOLYLINE[layer=="SLIDERS"]'), key=lambda e: -len(e))
    corners = np.array(list(block.get_points("xy")))
    assert block.closed and len(corners) == 4
    b = s.joints[0, s.joint_names.index("B")]
    np.testing.assert_allclose(corners.mean(axis=0), b, atol=1e-12)  # the block sits on B
    ends = np.array(list(guide.get_points("xy")))
    np.testing.assert_allclose(ends[:, 1], -5.0)  # the guide is the line y = -5 through G
