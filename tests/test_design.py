"""Walking-leg design search: core leg figures from Python, families, the NSGA-II search
(deterministic serially, on a LocalCluster and on a real scheduler with two workers),
checkpoints and resume, the report and the study files' messages."""

from __future__ import annotations

import dataclasses
import math
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import linkage
from linkage import _core

design = pytest.importorskip("linkage.design")

HERE = Path(__file__).resolve().parent
EXAMPLE = HERE.parent / "examples" / "studies" / "hoecken_family_study.toml"


def small(**kw):
    base = design.Study(
        family="fourbar",
        objectives=("stride", "straightness", "speed_variation"),
        population=16,
        budget=16 * 4,
        seed=7,
        settings=design.Settings(samples=180, foot_bar=100.0),
        constraints=design.Constraints(min_duty=0.0),
        chunk=12,
        name="small",
    )
    return dataclasses.replace(base, **kw)


def same(a, b):
    assert a.x.shape == b.x.shape
    np.testing.assert_array_equal(a.x, b.x)
    np.testing.assert_array_equal(a.figures, b.figures)  # NaN == NaN here
    np.testing.assert_array_equal(a.front, b.front)


# -- leg figures --------------------------------------------------------------------------


def test_core_figures_of_the_quadruped_leg():
    """The core's leg figures of the Hoecken foot path give the walker's quadruped figures
    (tests/test_walker.py: duty factor 0.58, stride 44.376 mm at a 0.1 mm ground tolerance)."""
    fb = linkage.catalog.hoecken()
    theta = np.linspace(0, 2 * np.pi, 1440, endpoint=False)
    s = fb.sweep(theta, omega=1.0, outputs=("velocity",))
    g, stance = _core.walking.leg_gait(
        np.ascontiguousarray(s.point), np.ascontiguousarray(s.velocity), 0.1
    )
    assert g["duty_factor"] == pytest.approx(0.58, abs=0.005)
    assert g["stride"] == pytest.approx(44.376, abs=0.01)
    assert g["lift"] == pytest.approx(2 * math.sqrt(600) - 40, abs=1e-9)
    assert g["stance_runs"] == 1 and stance.sum() == g["stance_count"]
    # The walker's simulation takes its stance and figures from the same code.
    sim = linkage.catalog.quadruped_hoecken().simulate(np.linspace(0, 2 * np.pi, 1441))
    assert len(sim.gaits) == 4
    np.testing.assert_array_equal(sim.duty_factor, sim.stance.mean(axis=0))
    for i, gi in enumerate(sim.gaits):
        assert gi["stance_count"] == sim.stance[:, i].sum()
    # Across sampling: 360 vs 1440 samples per turn.
    coarse = fb.sweep(theta[::4], omega=1.0, outputs=("velocity",))
    g4, _ = _core.walking.leg_gait(
        np.ascontiguousarray(coarse.point), np.ascontiguousarray(coarse.velocity), 0.1
    )
    assert abs(g4["duty_factor"] - g["duty_factor"]) < 2 / 360
    assert abs(g4["stride"] - g["stride"]) < 2 * g["peak_torque"] * 2 * np.pi / 360


def test_batched_figures_match_one_leg_and_any_thread_count():
    rng = np.random.default_rng(5)
    m = 300
    x = np.column_stack(
        [
            rng.uniform(12, 40, m),
            rng.uniform(-0.1, 0.1, m),
            rng.uniform(10, 50, m),
            rng.uniform(10, 50, m),
            rng.uniform(-20, 80, m),
            rng.uniform(-30, 30, m),
        ]
    )
    fam = design.family("fourbar")
    s = design.Settings(samples=240)
    one = fam.evaluate(x, s, threads=1)
    for threads in (2, 3, 7):
        np.testing.assert_array_equal(fam.evaluate(x, s, threads=threads), one)
    full = one[:, 0] == 1
    assert 0 < full.sum() < m  # some legs lock up: NaN figures, flagged
    assert np.isnan(one[~full, 3]).all()
    # A full-turn leg's figures by the multi-loop path (sweep + leg_gait) agree.
    i = int(np.flatnonzero(full)[0])
    mech = dataclasses.replace(fam, batched=False).evaluate(x[i : i + 1], s)[0]
    np.testing.assert_allclose(mech, one[i], rtol=1e-7, atol=1e-9)


def test_duty_factor_search_finds_the_stance_once_and_gives_the_same_answer():
    from linkage.drive import crank_schedule
    from linkage.gait_search import search_duty_factor

    q = linkage.catalog.quadruped_hoecken()
    betas = (0.55, 0.6)
    beta, margin = search_duty_factor(q, 80.0, "margin", duty_factors=betas)
    # The same search without the cache, written out.
    best = None
    for b in betas:
        sched = crank_schedule(q.legs[0].linkage, 80.0, b)
        t = np.linspace(0.0, sched.period, 721)
        v = q.simulate(time=t, drive=sched, per_leg_time=True).min_margin
        if best is None or v > best[1]:
            best = (b, v)
    assert (beta, margin) == best


def test_families_reference_designs():
    for name in design.FAMILIES:
        fam = design.family(name)
        assert len(fam.params) == len(fam.lower) == len(fam.upper) == len(fam.reference)
        assert all(lo <= r <= hi for lo, r, hi in zip(fam.lower, fam.reference, fam.upper))
        f = fam.evaluate(np.array([fam.reference]), design.Settings())[0]
        figs = dict(zip(design.FIGURES, f))
        assert figs["full_turn"] == 1 and figs["stride"] > 0 and figs["lift"] > 0
    hoecken = design.reference_figures(small())
    assert dict(zip(design.FIGURES, hoecken))["min_transmission"] == pytest.approx(
        math.degrees(math.acos(1150 / 1250))
    )
    # Jansen's holy numbers give the catalogue's Jansen foot path.
    fam = design.family("jansen")
    th = np.linspace(0, 2 * np.pi, 73)
    ours = fam.mechanism(fam.reference).sweep(th).point
    np.testing.assert_allclose(ours, linkage.catalog.jansen().sweep(th).point, atol=1e-9)
    with pytest.raises(linkage.LinkageError, match="unknown leg family"):
        design.family("theo")


def test_family_docstring_names_every_family():
    said = design.family.__doc__.splitlines()[0]
    missing = [n for n in design.FAMILIES if f"``{n}``" not in said]
    assert not missing, f"family's docstring does not name {missing}: {said!r}"


def test_exported_scene_runs_and_traces_the_same_foot():
    from linkage import scene

    study = small()
    x = np.array(design.family("fourbar").reference)
    sc = scene.parse(design.scene_text(study, x, "hoecken-export"), None)
    m = design.family("fourbar").mechanism(x)
    th = np.linspace(0, 2 * np.pi, 91)
    np.testing.assert_allclose(
        m.sweep(th).point, linkage.catalog.hoecken().sweep(th).point, atol=1e-9
    )
    assert sc.name == "hoecken-export"


# -- search -------------------------------------------------------------------------------


def test_same_seed_same_front_serial_and_local_cluster():
    a = design.search(small())
    assert a.evaluations == 64 and len(a.front) > 0
    same(a, design.search(small()))
    b = design.search(small(workers=2, chunk=5))
    same(a, b)
    assert not np.array_equal(a.x, design.search(small(seed=8)).x)


def test_real_scheduler_with_two_workers(tmp_path):
    exe = Path(sys.executable).with_name("dask")
    sched_file = tmp_path / "scheduler.json"
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(sys.path)}
    procs = [
        subprocess.Popen(
            [
                str(exe),
                "scheduler",
                "--scheduler-file",
                str(sched_file),
                "--port",
                "0",
                "--no-dashboard",
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            env=env,
        )
    ]
    try:
        for _ in range(300):
            if sched_file.exists() and sched_file.stat().st_size > 0:
                break
            time.sleep(0.1)
        import json

        address = json.loads(sched_file.read_text())["address"]
        for _ in range(2):
            procs.append(
                subprocess.Popen(
                    [
                        str(exe),
                        "worker",
                        address,
                        "--nworkers",
                        "1",
                        "--nthreads",
                        "1",
                        "--no-dashboard",
                    ],
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                    env=env,
                )
            )
        import distributed

        with distributed.Client(address, timeout="30s") as c:
            c.wait_for_workers(2, timeout=60)
        got = design.search(small(scheduler=address, chunk=5))
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
    same(design.search(small()), got)


def dominates(a, b):
    """Whether ``a`` dominates ``b`` (objectives minimised), row by row, broadcasting."""
    return np.all(a <= b, axis=-1) & np.any(a < b, axis=-1)


@pytest.mark.parametrize(
    "study",
    [
        small(),
        # The example study's constraints: no design of 200 000 drawn uniformly over the box
        # meets duty factor >= 0.4, so a search from the box alone finds nothing in 4 generations.
        small(
            objectives=("stride", "straightness", "speed_variation", "duty_factor"),
            constraints=design.Constraints(foot_below_hip=20.0, min_lift=4.0, min_duty=0.4),
        ),
    ],
    ids=["min-duty-0", "example-constraints"],
)
def test_front_holds_the_reference_or_designs_dominating_it(study):
    res = design.search(study)
    ref = design.reference_figures(study)
    f_ref, g_ref = design.objectives_and_constraints(study, ref[None, :])
    assert (g_ref <= 0).all()
    f, g = design.objectives_and_constraints(study, res.front_figures())
    assert (g <= 0).all()
    assert not dominates(f_ref[0], f).any()
    assert (f == f_ref[0]).all(axis=1).any() or dominates(f, f_ref[0]).any()
    place = design.placement(study, res)
    assert place["feasible"] and place["dominates"] == []
    assert len(place["dominated_by"]) == int(dominates(f, f_ref[0]).sum())
    ref_x = design.family("fourbar").reference
    assert place["on_front"] == bool((res.front_x() == ref_x).all(axis=1).any())


def test_a_leg_without_a_full_turn_is_worst_and_violates_every_constraint():
    # Coupler and rocker of 5 cannot reach across a ground of 20: no sample assembles.
    study = small()
    figs = design.family("fourbar").evaluate(
        np.array([[20.0, 0.0, 5.0, 5.0, 50.0, 0.0]]), study.settings
    )
    f, g = design.objectives_and_constraints(study, figs)
    np.testing.assert_array_equal(f, [[1e12, 1e12, 1e12]], err_msg="worst objectives")
    # full turn and one stance run by 1 (figures 0 and 0), the rest (NaN figures) by 10
    np.testing.assert_array_equal(g, [[1.0, 1.0, 10.0, 10.0, 10.0, 10.0]], err_msg="violations")


def test_first_population_is_the_reference_its_neighbours_and_the_box():
    study = small(population=32)
    x = design.initial_population(study)
    xl, xu = study.box()
    ref = np.array(design.family("fourbar").reference)
    assert x.shape == (32, 6) and ((xl <= x) & (x <= xu)).all()
    np.testing.assert_array_equal(x[0], ref)
    near = np.abs(x[1:5] - ref) <= 0.02 * (xu - xl)
    assert near.all() and not (np.abs(x[5:] - ref) <= 0.02 * (xu - xl)).all(axis=1).any()
    np.testing.assert_array_equal(x, design.initial_population(study))
    assert not np.array_equal(x, design.initial_population(small(population=32, seed=8)))
    np.testing.assert_array_equal(design.search(study).x[:32], x)
    # A reference outside the study's bounds is left out, and so are its neighbours.
    away = design.initial_population(small(bounds={"ground": (30.0, 40.0)}))
    assert (away[:, 0] >= 30.0).all() and not (away == ref).all(axis=1).any()


def test_stopped_search_resumes_to_the_same_front(tmp_path):
    ck = tmp_path / "run.checkpoint"
    whole = design.search(small())
    part = design.search(small(), checkpoint=ck, stop_after=2)
    assert part.generations == 2 and ck.exists()
    resumed = design.search(small(), checkpoint=ck)
    assert resumed.generations == 4
    same(whole, resumed)
    # A checkpoint of another study is refused, and a file that is not one is left alone.
    with pytest.raises(linkage.LinkageError, match="different study"):
        design.search(small(seed=9), checkpoint=ck)
    foreign = tmp_path / "notes.txt"
    foreign.write_text("mine")
    with pytest.raises(linkage.LinkageError, match="not a"):
        design.search(small(), checkpoint=foreign)
    assert foreign.read_text() == "mine"


def test_killed_cli_search_resumes_to_the_same_front(tmp_path):
    study = tmp_path / "s.toml"
    study.write_text(
        'name = "killed"\n[design]\nfamily = "fourbar"\npopulation = 16\nbudget = 320\n'
        "seed = 4\nsamples = 120\nfoot_bar = 100.0\nchoose = 2\n"
        "[design.constraints]\nmin_duty = 0.1\n"
    )
    out, ck = tmp_path / "rep", tmp_path / "ck.pkl"
    cmd = [
        sys.executable,
        "-m",
        "linkage",
        "design",
        str(study),
        "--out",
        str(out),
        "--checkpoint",
        str(ck),
        "--quiet",
    ]
    p = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(600):
        if ck.exists() or p.poll() is not None:
            break
        time.sleep(0.01)
    p.send_signal(signal.SIGKILL)
    p.wait()
    assert ck.exists() and not out.exists()
    assert subprocess.run(cmd, capture_output=True).returncode == 0
    sf = design.load_study(study)
    whole = design.search(sf.study)
    got = np.loadtxt(out / "front.csv", delimiter=",", skiprows=1, ndmin=2)
    np.testing.assert_allclose(got[:, :6], whole.front_x(), rtol=1e-9)


def test_report_files_and_safety(tmp_path):
    res = design.search(small())
    out = tmp_path / "rep"
    files = {p.name for p in design.write_report(res, out, choose=2)}
    assert {"front.csv", "pareto.png", "summary.json", "design-1.toml"} <= files
    assert files & {"candidates.csv", "candidates.parquet"}
    from linkage import scene

    scene.load(out / "design-1.toml")
    import json

    ref = json.loads((out / "summary.json").read_text())["reference"]
    assert ref["dominates_count"] == 0 == len(ref["dominates"])
    assert ref["dominated_by_count"] == len(ref["dominated_by"])
    with pytest.raises(linkage.LinkageError, match="earlier report"):
        design.write_report(res, out)
    design.write_report(res, out, force=True)
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "thesis.txt").write_text("keep")
    with pytest.raises(linkage.LinkageError, match="not a report"):
        design.write_report(res, mine, force=True)
    assert (mine / "thesis.txt").read_text() == "keep"


# -- study files --------------------------------------------------------------------------


@pytest.mark.parametrize(
    "body, line, key, words",
    [
        ('[design]\nfamily = "theo"\n', 2, "family", "unknown family"),
        ('[design]\nfamily = "fourbar"\npopulaton = 3\n', 3, "populaton", "unknown key"),
        ("[design]\npopulation = 2\n", 2, "population", "between"),
        ('[design]\nobjectives = ["speed"]\n', 2, "objectives", "unknown objective"),
        ("[design]\n[design.bounds]\ncoupler = [30, 10]\n", 3, "coupler", "lower < upper"),
        ("[design]\n[design.bounds]\nfoot = [1, 2]\n", 3, "foot", "no parameter"),
        ('[design]\n[design.constraints]\nmin_lift = "x"\n', 3, "min_lift", "finite"),
        ("[design]\nseed = 1.5\n", 2, "seed", "must be int"),
        ('[design]\nworkers = 2\nscheduler = "tcp://x:1"\n', 3, "scheduler", "not both"),
    ],
)
def test_bad_study_files_name_file_line_and_key(tmp_path, body, line, key, words):
    p = tmp_path / "bad.toml"
    p.write_text(body)
    with pytest.raises(linkage.LinkageError) as e:
        design.load_study(p)
    msg = str(e.value)
    assert msg.startswith(f"{p}:{line}:") and key in msg and words in msg, msg


def test_cli_reports_bad_study_without_traceback(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text("[design]\nbudget = 1\n")
    r = subprocess.run(
        [sys.executable, "-m", "linkage", "design", str(p)], capture_output=True, text=True
    )
    assert r.returncode != 0 and f"{p}:2:" in r.stderr and "Traceback" not in r.stderr


def test_example_study_loads():
    sf = design.load_study(EXAMPLE)
    assert sf.study.family == "fourbar" and sf.study.workers == 2


def test_missing_optional_packages_give_a_clear_import_error(monkeypatch):
    monkeypatch.setitem(sys.modules, "pymoo", None)
    monkeypatch.delitem(sys.modules, "linkage.design")
    for k in [k for k in sys.modules if k.startswith("pymoo.")]:
        monkeypatch.delitem(sys.modules, k)
    with pytest.raises(ImportError, match=r"pip install 'linkage-kinematics\[design\]'"):
        import linkage.design  # noqa: F401


def test_guided_six_bar_family_searches_and_its_reference_walks_hoecken():
    """The second six-bar family: its reference is Hoecken's foot path (figures equal to the
    four-bar family's reference), and a small search over it runs and finds feasible legs."""
    fam, four = design.family("guided"), design.family("fourbar")
    g = fam.evaluate(np.array([fam.reference]), design.Settings())[0]
    h = four.evaluate(np.array([four.reference]), design.Settings())[0]
    for name in ("duty_factor", "stride", "lift", "straightness"):
        k = design.FIGURES.index(name)
        assert g[k] == pytest.approx(h[k], rel=1e-9, abs=1e-9), name
    front = design.search(small(family="guided"))
    assert front.evaluations == 64 and len(front.front) > 0
