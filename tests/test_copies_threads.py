"""Copies, threads and pickling of the linkage objects (issue 29, items 8 and 10).

A point-only sweep completes itself on first use; copies and threads must each see a whole
state. A mechanism swept while another thread extends it must give columns that match its
names. ``FourBar``, ``SliderCrank``, ``Mechanism``, ``Sweep`` and synthesis ``Candidate``
pickle (through their validating constructors) and compare by value.
"""

from __future__ import annotations

import copy
import pickle
import sys
import threading
import time

import numpy as np
import pytest

import linkage
from linkage import FourBar, LinkageError, Mechanism, SliderCrank, Sweep
from linkage.synthesis import Candidate

TH = np.linspace(0.0, 2 * np.pi, 181)


def linkages() -> list[object]:
    """One of each kind, with every kind of construction a mechanism can hold."""
    m = Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("C", (3, 0.25))
    m.crank("A", "O", 1, phase=0.25)
    m.slider("S", "A", 3, origin="C", direction=(3, 4.1))  # a direction the core normalises
    m.slider("T", "A", 3.5, origin="C", link=("O", "A"), angle=0.5, reach="behind")
    m.dyad("B", "A", "C", 3, 3.5, side="right")
    m.point("P", on=("A", "B"), at=(1, 2))
    m.trace = "B"
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 3), o=(1, 2))
    sc = SliderCrank(crank=2, coupler=5, offset=1, point=(2.5, 0.5), angle=0.3, reach="behind")
    return [
        fb,
        *fb.cognates(),
        fb.reversed(),
        linkage.catalog.hoecken(),
        sc,
        sc.cognate(),
        m,
        fb.mechanism(),
        sc.mechanism(),
        linkage.catalog.jansen(),
        linkage.catalog.peaucellier(),
    ]


@pytest.mark.parametrize("obj", linkages(), ids=lambda o: type(o).__name__)
def test_linkages_pickle_and_copy_equal(obj):
    for other in (
        pickle.loads(pickle.dumps(obj)),
        copy.deepcopy(obj),
        copy.copy(obj),
    ):
        assert other == obj and other is not obj
        assert type(other) is type(obj)
        if isinstance(obj, Mechanism):
            assert other.joint_names == obj.joint_names and other.links == obj.links
            assert other.trace == obj.trace
            a, b = (
                obj.sweep(TH, omega=1.0, outputs=("joints", "velocity")),
                other.sweep(TH, omega=1.0, outputs=("joints", "velocity")),
            )
        else:
            assert hash(other) == hash(obj)
            assert repr(other) == repr(obj)
            a, b = obj.sweep(TH), other.sweep(TH)
        for key in ("joints", "valid", "gap", "margin"):
            assert np.array_equal(getattr(a, key), getattr(b, key), equal_nan=True), key


def test_equal_parameters_make_equal_fourbars():
    a = FourBar(ground=20, crank=10, coupler=25, rocker=25)
    assert a == FourBar(ground=20, crank=10, coupler=25, rocker=25)
    assert a == FourBar(crank=10, coupler=25, rocker=25, c=(20, 0))  # the same linkage
    assert a != FourBar(ground=20, crank=10, coupler=25, rocker=25, assembly="crossed")
    assert a != FourBar(ground=20, crank=10, coupler=25, rocker=25.000001)
    assert len({a, FourBar(ground=20, crank=10, coupler=25, rocker=25)}) == 1
    assert a != a.mechanism() and a.mechanism() == a.mechanism()
    assert SliderCrank(crank=2, coupler=5) == SliderCrank(crank=2, coupler=5, offset=0.0)
    assert SliderCrank(crank=2, coupler=5) != SliderCrank(crank=2, coupler=5, reach="behind")


def test_mechanisms_compare_by_program():
    def build(r2: float) -> Mechanism:
        m = Mechanism()
        m.fixed("O", (0, 0))
        m.fixed("C", (2, 0))
        m.crank("A", "O", 1)
        m.dyad("B", "A", "C", 2, r2)
        return m

    a, b = build(2), build(2)
    assert a == b and a != build(2.5)
    with pytest.raises(TypeError):
        hash(a)  # mutable
    b.point("P", on=("A", "B"), at=(1, 0))
    assert a != b
    c = copy.copy(a)
    c.trace = "A"
    assert a != c and a.trace == "B"


def test_a_copy_of_a_mechanism_is_independent():
    m = linkage.catalog.hoecken().mechanism()
    c = copy.deepcopy(m)
    c.point("Q", on=("A", "B"), at=(10, 0))
    assert m.joint_names == ("O", "C", "A", "B", "P")
    assert c.joint_names == ("O", "C", "A", "B", "P", "Q")
    assert m.sweep(TH).joints.shape == (TH.size, 5, 2)
    assert c.sweep(TH).joints.shape == (TH.size, 6, 2)
    np.testing.assert_array_equal(c.sweep(TH).joints[:, :5], m.sweep(TH).joints)


@pytest.mark.parametrize(
    "which", [0, 5, 7, 10], ids=["fourbar", "slider-crank", "sliders", "jansen"]
)
def test_a_mechanism_extended_after_a_sweep_keeps_its_joints_bit_for_bit(which):
    # The swept core is shared with the sweep, so the new joint goes to a copy of the program:
    # the same calls, hence the same bits (a slider's direction is normalised by the core).
    obj = linkages()[which]
    m = obj if isinstance(obj, Mechanism) else obj.mechanism()
    before = m.sweep(TH).joints
    n = len(m)
    m.point("extra", on=(m.joint_names[0], m.joint_names[2]), at=(1.0, 1.0))
    after = m.sweep(TH).joints
    assert after.shape == (TH.size, n + 1, 2)
    np.testing.assert_array_equal(after[:, :n], before)
    assert pickle.loads(pickle.dumps(m)) == m


def test_unpickling_checks_the_values_again():
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25)
    func, args = fb.__reduce__()
    with pytest.raises(LinkageError, match="crank must be a positive finite length"):
        func(*args[:1], -10.0, *args[2:])
    sc = SliderCrank(crank=2, coupler=5)
    func, args = sc.__reduce__()
    with pytest.raises(LinkageError, match="reach must be"):
        func(*args[:-1], "sideways")
    m = linkage.catalog.hoecken().mechanism()
    func, args = m.__reduce__()
    base, calls, trace = args
    with pytest.raises(LinkageError, match="already defined"):
        func(base, (("fixed", "O", (9.0, 9.0)),), trace)
    with pytest.raises(LinkageError, match="not a building call"):
        func(base, (("system", "rm -rf"),), trace)
    with pytest.raises(TypeError, match="not a pickled Mechanism"):
        func("os.system", (), None)
    j = linkage.catalog.jansen()
    func, (base, calls, trace) = j.__reduce__()
    bad = list(calls)
    bad[3] = (*bad[3][:-2], -1.0, bad[3][-1])  # a dyad with a negative length
    with pytest.raises(LinkageError, match="positive finite length"):
        func(base, tuple(bad), trace)
    s = fb.sweep(TH)
    func, (lk, method, arguments, times) = s.__reduce__()
    with pytest.raises(LinkageError, match="must be finite"):
        func(lk, method, {**arguments, "theta": np.array([0.0, np.inf])}, times)
    with pytest.raises(LinkageError, match="not a pickled Sweep"):
        func(lk, "__init__", arguments, times)
    with pytest.raises(LinkageError, match="not a pickled Sweep"):
        func(lk, method, {**arguments, "out": None}, times)
    with pytest.raises(LinkageError, match="times do not match"):
        func(lk, method, arguments, np.zeros(3))


# -- sweeps -----------------------------------------------------------------------------------


def sweeps() -> list[Sweep]:
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 3))
    m = linkage.catalog.jansen()
    from linkage.drive import ConstantSpeed

    return [
        fb.sweep(TH, outputs=("point",)),
        fb.sweep(1.0, omega=2.0, outputs=("point", "velocity", "curvature")),
        fb.sweep(TH, outputs=("instant_centres",), pairs=[("ground", "coupler")]),
        fb.circuit(31),
        SliderCrank(crank=2, coupler=2.5, offset=1).circuit(17),
        m.sweep(TH, omega=1.0, alpha=np.linspace(0, 1, TH.size), outputs=("point", "velocity")),
        m.sweep(time=[0.0, 0.1, 0.2], drive=ConstantSpeed(omega=3.0)),
    ]


@pytest.mark.parametrize("s", sweeps(), ids=lambda s: repr(s.outputs))
def test_sweeps_pickle_and_copy_equal(s):
    for other in (pickle.loads(pickle.dumps(s)), copy.deepcopy(s), copy.copy(s)):
        assert other == s and other is not s
        assert other.joint_names == s.joint_names and other.links == s.links
        assert other.outputs == s.outputs and other.link_pairs == s.link_pairs
        for key in ("theta", "time", "point", "joints", "valid", "margin", "gap", "regular"):
            a, b = getattr(s, key), getattr(other, key)
            assert (a is None and b is None) or np.array_equal(a, b, equal_nan=True), key
        for key in ("velocity", "joint_velocities", "curvature", "instant_centres"):
            if any(key.endswith(o.rstrip("s")) or o in key for o in s.outputs):
                np.testing.assert_array_equal(getattr(other, key), getattr(s, key))
    with pytest.raises(TypeError):
        hash(s)


def test_sweeps_compare_by_linkage_and_inputs():
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25)
    a = fb.sweep(TH)
    assert a == FourBar(ground=20, crank=10, coupler=25, rocker=25).sweep(TH.copy())
    assert a == fb.mechanism().sweep(TH)  # the same program: the same sweep
    assert a != fb.sweep(TH[:-1])
    assert a != fb.sweep(TH, outputs=("point",))
    assert a != fb.sweep(TH, omega=1.0)
    assert a != FourBar(ground=20, crank=10, coupler=25, rocker=24).sweep(TH)
    assert a != fb.circuit(TH.size)
    assert fb.circuit(11) == fb.circuit(11) != fb.circuit(12)


@pytest.mark.parametrize("how", [copy.copy, copy.deepcopy, lambda s: s])
def test_point_only_sweep_copied_then_read_on_both(how):
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 3))
    full = fb.sweep(TH, omega=1.0, outputs=("joints", "velocity"))
    for first in ("joints", "margin", "joint_velocities"):
        s = fb.sweep(TH, omega=1.0, outputs=("point", "velocity"))
        c = how(s)
        # Reading one completes it; the other then completes on its own (no false "changed").
        for x in (s, c, s, c):
            getattr(x, first)
            np.testing.assert_array_equal(x.joints, full.joints)
            np.testing.assert_array_equal(x.margin, full.margin)
            np.testing.assert_array_equal(x.point, full.point)
            np.testing.assert_array_equal(x.velocity, full.velocity)
            np.testing.assert_array_equal(x.joint_velocities, full.joint_velocities)


def test_eight_threads_read_one_sweep():
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 3))
    th = np.linspace(0.0, 2 * np.pi, 2001)
    full = fb.sweep(th, omega=1.0, outputs=("joints", "velocity", "curvature"))
    readers = (
        "joints",
        "margin",
        "gap",
        "regular",
        "point",
        "velocity",
        "joint_velocities",
        "curvature",
        "curvature_centre",
        "joint_curvatures",
    )
    errors: list[BaseException] = []
    wrong: list[str] = []
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)  # switch threads as often as possible
    try:
        for trial in range(40):
            s = fb.sweep(th, omega=1.0, outputs=("point", "velocity", "curvature"))
            start = threading.Barrier(8)

            def read(k: int, s: Sweep = s, start: threading.Barrier = start) -> None:
                try:
                    start.wait()
                    for name in readers[k % 3 :] + readers[: k % 3]:
                        if not np.array_equal(
                            getattr(s, name), getattr(full, name), equal_nan=True
                        ):
                            wrong.append(name)
                except BaseException as exc:  # reported below
                    errors.append(exc)

            threads = [threading.Thread(target=read, args=(k,)) for k in range(8)]
            for t in threads:
                t.start()
            for t in threads:
                t.join()
            assert not errors, f"trial {trial}: {errors[0]!r}"
            assert not wrong, f"trial {trial}: {wrong}"
    finally:
        sys.setswitchinterval(interval)


def test_a_point_only_sweep_completed_after_joints_were_added():
    m = linkage.catalog.hoecken().mechanism()
    s = m.sweep(TH, outputs=("point",))
    m.point("Q", on=("A", "B"), at=(10, 0))
    assert s.joint_names == ("O", "C", "A", "B", "P")
    assert s.joints.shape == (TH.size, 5, 2)  # the mechanism as it was when swept
    assert m.sweep(TH, outputs=("point",)).joints.shape == (TH.size, 6, 2)


def test_mechanism_swept_while_another_thread_adds_joints():
    th = np.linspace(0.0, 1.0, 16)
    ref = linkage.catalog.hoecken().sweep(th).joints
    bad: list[tuple[int, tuple[str, ...], str]] = []
    sweeps = rounds = 0
    interval = sys.getswitchinterval()
    sys.setswitchinterval(1e-6)
    try:
        t0 = time.perf_counter()
        while (sweeps < 600 or rounds < 5) and time.perf_counter() - t0 < 8:
            m = linkage.catalog.hoecken().mechanism()

            def grow(m: Mechanism = m) -> None:
                for k in range(58):  # the core holds 64 joints
                    m.point(f"Q{k}", on=("A", "B"), at=(k, 1.0))
                    time.sleep(0)

            grower = threading.Thread(target=grow)
            grower.start()
            while grower.is_alive():
                for outputs in (("joints",), ("point",)):
                    s = m.sweep(th, outputs=outputs)
                    n = len(s.joint_names)
                    try:
                        joints = s.joints  # a point-only sweep computes them now
                    except LinkageError as exc:
                        bad.append((sweeps, outputs, str(exc)[:60]))
                    else:
                        if joints.shape[1] != n or not np.array_equal(joints[:, :5], ref):
                            bad.append((sweeps, outputs, f"{n} names, {joints.shape}"))
                    sweeps += 1
            grower.join()
            rounds += 1
    finally:
        sys.setswitchinterval(interval)
    assert sweeps >= 600, sweeps
    assert not bad, f"{len(bad)} of {sweeps} sweeps had inconsistent columns: {bad[:3]}"


# -- synthesis candidates -------------------------------------------------------------------


def candidate(back: float) -> Candidate[FourBar]:
    return Candidate(
        linkage=FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 3)),
        error=0.5,
        rms=0.25,
        back=back,
        crank_range=(0.0, 2 * np.pi),
        full_turn=True,
        grashof="crank-rocker",
        min_transmission=0.4,
        through_limit=False,
        source="atlas",
        params=np.array([20.0, 10.0, 25.0, 25.0, 50.0, 3.0]),
    )


@pytest.mark.parametrize("back", [0.75, float("nan")])
def test_candidates_pickle_and_copy_equal(back):
    c = candidate(back)
    for other in (pickle.loads(pickle.dumps(c)), copy.deepcopy(c), copy.copy(c)):
        assert other == c and other is not c
    assert c != candidate(1.5) and c != Candidate(**{**vars(c), "params": c.params[:-1]})
    sc = Candidate(
        **{**vars(c), "linkage": SliderCrank(crank=2, coupler=5), "kind": "slider-crank"}
    )
    assert pickle.loads(pickle.dumps(sc)) == sc != c


# -- through a Dask worker ------------------------------------------------------------------


def test_round_trip_through_a_dask_worker():
    distributed = pytest.importorskip("distributed")
    fb = FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(50, 3))
    objs = [fb, SliderCrank(crank=2, coupler=5), fb.mechanism(), fb.sweep(TH), candidate(0.75)]
    # A worker process (not threads of this one): every object crosses by pickle, both ways.
    with (
        distributed.LocalCluster(
            n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None
        ) as cluster,
        distributed.Client(cluster, timeout="60s") as client,
    ):
        futures = [client.submit(lambda x: (x, x == copy.deepcopy(x)), o, pure=False) for o in objs]
        distributed.wait(futures, timeout=60)
        back = client.gather(futures, errors="raise")
        pid = client.submit(lambda: __import__("os").getpid(), pure=False).result()
    import os

    assert pid != os.getpid()
    for o, (got, equal_there) in zip(objs, back):
        assert equal_there and got == o and got is not o
    assert np.array_equal(back[3][0].joints, objs[3].joints)


# -- masked arrays (item 10) ------------------------------------------------------------------


def test_masked_arrays_are_refused_not_swept_as_valid():
    fb = linkage.catalog.hoecken()
    th = np.ma.masked_array([0.0, 1.0, 2.0], mask=[False, True, False])
    for call in (
        lambda: fb.sweep(th),
        lambda: fb.transmission_angle(th),
        lambda: fb.mechanism().sweep([0.0, 1.0], omega=np.ma.masked_array([1.0, 2.0], mask=[1, 0])),
        lambda: SliderCrank(crank=2, coupler=5).sweep(th),
        lambda: linkage.synthesis.read_points(
            np.ma.masked_array([[0.0, 0], [1, 1], [2, 3]], mask=[[0, 0], [1, 0], [0, 0]])
        ),
    ):
        with pytest.raises(TypeError, match=r"masked array with 1 masked value.*not taken"):
            call()
    # With nothing masked, the values are all valid: taken as they are.
    clear = np.ma.masked_array([0.0, 1.0, 2.0], mask=False)
    np.testing.assert_array_equal(fb.sweep(clear).point, fb.sweep(clear.data).point)


def test_unaligned_contiguous_arrays_are_taken():
    # What pickle protocol 5 (Dask) can hand back: float64, C-contiguous, not aligned.
    fb = linkage.catalog.hoecken()
    raw = np.zeros(8 * TH.size + 1, dtype=np.uint8)
    th = raw[1:].view(np.float64)
    th[:] = TH
    assert th.flags.c_contiguous and not th.flags.aligned
    w = raw[1 : 1 + 8 * TH.size].view(np.float64)
    s = fb.mechanism().sweep(th, omega=w, outputs=("point", "velocity"))
    np.testing.assert_array_equal(s.point, fb.sweep(TH).point)
    np.testing.assert_array_equal(
        s.velocity, fb.sweep(TH, omega=TH, outputs=("point", "velocity")).velocity
    )
