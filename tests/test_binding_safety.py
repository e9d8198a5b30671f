"""The extension raises only LinkageError, TypeError and MemoryError (issue 10).

Each test calls ``linkage._core`` the way a hostile caller would: counts that are negative or
beyond 2**63, ints too large for a float, outputs too large for the machine, NaN-producing
coordinates, threads racing on one mechanism. A Rust panic would surface as
``pyo3_runtime.PanicException`` (a BaseException that ``pytest.raises(Exception)`` does not
catch), an abort would kill the process: allocation tests therefore run in a child process
under an address-space limit, so a failure cannot take pytest down.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
import threading

import numpy as np
import pytest

from linkage import _core
from linkage._core import LinkageError


def _hoecken(scale: float = 1.0) -> _core.FourBar:
    s = scale
    return _core.FourBar((0.0, 0.0), (20 * s, 0.0), 10 * s, 25 * s, 25 * s, (50 * s, 0.0), "open")


def _run_limited(code: str, limit_bytes: int = 1 << 30) -> subprocess.CompletedProcess[str]:
    """Runs `code` in a child Python under RLIMIT_AS = `limit_bytes`."""
    prelude = textwrap.dedent(
        f"""
        import resource
        resource.setrlimit(resource.RLIMIT_AS, ({limit_bytes}, {limit_bytes}))
        """
    )
    return subprocess.run(
        [sys.executable, "-c", prelude + textwrap.dedent(code)],
        capture_output=True,
        text=True,
        timeout=120,
        env={"RUST_BACKTRACE": "0", "PATH": "/usr/bin:/bin"},
    )


# Counts and indices: LinkageError naming the argument, never OverflowError or a wrap.


@pytest.mark.parametrize("n", [-1, 2**63, 2**64 + 3, 10**40])
def test_uniform_sweep_absurd_n_is_linkage_error_naming_n(n: int) -> None:
    with pytest.raises(LinkageError, match=r"\bn\b"):
        _hoecken().uniform_sweep(0.0, 0.1, n)


@pytest.mark.parametrize(("kw", "value"), [("block", -5), ("threads", 2**64), ("threads", -1)])
def test_uniform_sweep_absurd_block_or_threads_names_them(kw: str, value: int) -> None:
    with pytest.raises(LinkageError, match=kw):
        _hoecken().uniform_sweep(0.0, 0.1, 10, **{kw: value})


def test_counts_must_be_integers() -> None:
    with pytest.raises(TypeError, match=r"\bn\b"):
        _hoecken().uniform_sweep(0.0, 0.1, 10.5)  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="centre"):
        _core.Mechanism().crank("0", 1.0)  # type: ignore[arg-type]
    # numpy integers are integers.
    assert _hoecken().uniform_sweep(0.0, 0.1, np.int64(3)).shape == (3, 2)


@pytest.mark.parametrize("n", [-1, 2**64])
def test_circuit_absurd_n_is_linkage_error(n: int) -> None:
    with pytest.raises(LinkageError, match=r"\bn\b"):
        _hoecken().circuit(n)


def test_joint_indices_out_of_range_are_linkage_errors() -> None:
    m = _core.Mechanism()
    m.fixed(0.0, 0.0)
    with pytest.raises(LinkageError, match="centre"):
        m.crank(-1, 1.0)
    with pytest.raises(LinkageError, match="p1"):
        m.dyad(2**70, 0, 1.0, 1.0, "left")
    with pytest.raises(LinkageError, match="to"):
        m.point(0, -3, 1.0, 0.0)
    with pytest.raises(LinkageError):
        m.crank(2**40, 1.0)  # fits, but refers to no joint


def test_float_arguments_too_large_for_a_float_are_linkage_errors() -> None:
    with pytest.raises(LinkageError, match="too large for a float"):
        _core.Mechanism().fixed(10**400, 0.0)
    with pytest.raises(LinkageError, match="too large for a float"):
        _core.FourBar((0, 0), (10**309, 0), 1, 1, 1, (0, 0), "open")
    with pytest.raises(LinkageError, match="too large for a float"):
        _core.drive.evaluate_program(0.0, [10**400], [1.0], [None], np.zeros(1))


def test_gear_teeth_beyond_u32_and_ratio_underflow_are_linkage_errors() -> None:
    with pytest.raises(LinkageError, match="tooth count"):
        _core.drive.simple_gear_train([1, 2**40])
    with pytest.raises(LinkageError, match="tooth count"):
        _core.drive.simple_gear_train([-1, 3])
    with pytest.raises(LinkageError, match="driven teeth"):
        _core.drive.compound_gear_train([(1, 2**63)])
    # 1e-360 has no float: an error, not a ratio of 0.
    with pytest.raises(LinkageError, match="gear train ratio"):
        _core.drive.compound_gear_train([(1, 10**9)] * 40)
    # Far outside the float range on the way, exactly 1 at the end.
    ratio, sign = _core.drive.compound_gear_train([(1, 10**9)] * 40 + [(10**9, 1)] * 40)
    assert ratio == pytest.approx(1.0, rel=1e-13) and sign == 1


# Sizes beyond the machine: MemoryError naming the size.


def test_sweep_beyond_any_address_space_is_memory_error_naming_size() -> None:
    with pytest.raises(
        MemoryError, match=r"sweep of 4611686018427387904 samples needs .* [GTPE]iB \("
    ):
        _hoecken().uniform_sweep(0.0, 0.1, 2**62)
    with pytest.raises(MemoryError, match=r"circuit of 2305843009213693952 samples needs"):
        _hoecken().circuit(2**61)


def test_sweep_beyond_this_machine_is_memory_error() -> None:
    # 10**13 samples need 160 TB: more than any test machine has, but within isize. (In a
    # child: without the size check this aborts the process.)
    child = _run_limited(
        """
        from linkage import _core
        fb = _core.FourBar((0, 0), (20, 0), 10, 25, 25, (50, 0), "open")
        try:
            fb.uniform_sweep(0.0, 0.1, 10**13)
        except MemoryError as e:
            print("MemoryError:", e)
        """,
        limit_bytes=1 << 62,
    )
    assert child.returncode == 0, child.stderr[-2000:]
    want = "sweep of 10000000000000 samples needs 146 TiB (160000000000000 bytes)"
    assert want in child.stdout, child.stdout


@pytest.mark.parametrize(
    "call",
    [
        "fb.uniform_sweep(0.0, 1e-3, 10**9)",  # 16 GB
        "fb.uniform_sweep(0.0, 1e-3, 10**9, threads=2)",
        "fb.circuit(10**8)",  # 16.8 GB
        # 3e6 samples of Hart's inversor with instant centres: ~4 GB of outputs.
        "m.sweep(np.linspace(0, 1, 3 * 10**6), instant_centres=True, curvature=True)",
        "_core.drive.evaluate_motion_law('cycloidal', np.zeros(10**8))",  # 3.2 GB out of 0.8 GB in
    ],
)
def test_allocation_refused_under_address_space_limit_is_memory_error(call: str) -> None:
    child = _run_limited(
        f"""
        import numpy as np
        from linkage import _core
        fb = _core.FourBar((0, 0), (20, 0), 10, 25, 25, (50, 0), "open")
        m = _core.catalog.linkage("hart")[0]
        try:
            {call}
        except MemoryError as e:
            print("MemoryError:", e)
        """,
        limit_bytes=2 << 30,
    )
    assert child.returncode == 0, child.stderr[-2000:]
    assert "MemoryError:" in child.stdout and "iB (" in child.stdout, child.stdout + child.stderr


# Panics reachable from Python before issue 10.


def test_hull_with_overflowing_orientation_tests_does_not_panic() -> None:
    big = 1e308
    pts = np.array(
        [[[big, big], [-big, -big], [big, -big], [-big, big], [0.0, big], [np.nan, 0.0]]]
    )
    margin, hull, count = _core.walking.support_margins(pts, np.zeros((1, 2)))
    assert count[0] == 4
    assert margin[0] == big
    assert np.isfinite(hull[0, :4]).all() and np.isnan(hull[0, 4:]).all()


def test_hull_random_extreme_points_never_panic() -> None:
    rng = np.random.default_rng(7)
    choices = np.array([np.nan, np.inf, -np.inf, 0.0, 1e308, -1e308, 5e-324, 1.0, -1.0])
    pts = rng.choice(choices, size=(500, 6, 2))
    cg = rng.choice(choices, size=(500, 2))
    margin, _, count = _core.walking.support_margins(pts, cg)
    assert margin.shape == (500,) and (count <= 7).all()


def test_pantograph_at_huge_scale_is_linkage_error() -> None:
    with pytest.raises(LinkageError, match="pantograph scale"):
        _core.catalog.linkage("hoecken_pantograph", 1e308)


def test_messages_say_what_is_wrong_not_a_length_template() -> None:
    # A new user's trial: a gear count and a scale of 0.5 had been "not a positive finite length".
    import linkage

    cases = [
        (
            lambda: linkage.catalog.hoecken_pantograph(0.5),
            "pantograph scale must be greater than 1, got 0.5",
        ),
        (
            lambda: linkage.catalog.hoecken_pantograph(float("nan")),
            "scale must be finite",
        ),
        (
            lambda: linkage.drive.GearTrain.simple([18]),
            "needs at least 2 gears in a simple gear train, got 1",
        ),
        (
            lambda: linkage.drive.GearTrain.simple([18, 0]),
            "tooth counts must be positive, got 0",
        ),
        (
            lambda: linkage.drive.GearTrain.compound([]),
            "needs at least 1 stages in a compound gear train, got 0",
        ),
    ]
    for make, message in cases:
        with pytest.raises(LinkageError) as info:
            make()
        assert str(info.value).startswith(message), str(info.value)
        assert "positive finite length" not in str(info.value), str(info.value)


def test_many_threads_are_capped_and_give_the_same_bits() -> None:
    fb = _hoecken()
    one = fb.uniform_sweep(0.3, 1e-3, 20_000, threads=1)
    many = fb.uniform_sweep(0.3, 1e-3, 20_000, threads=100_000)
    assert np.array_equal(one, many, equal_nan=True)


def test_misaligned_out_array_is_refused() -> None:
    buf = bytearray(8 * 20 + 1)
    out = np.frombuffer(buf, dtype=np.float64, offset=1, count=20).reshape(10, 2)
    assert out.flags.writeable and not out.flags.aligned
    with pytest.raises(LinkageError):
        _hoecken().uniform_sweep(0.0, 0.1, 10, out=out)


def test_mechanism_shared_between_threads_never_reports_a_borrow() -> None:
    m, _, _ = _core.catalog.linkage("hart")
    theta = np.linspace(0.0, 6.0, 20_000)
    errors: list[BaseException] = []

    def sweeper() -> None:
        try:
            for _ in range(20):
                m.sweep(theta, velocity=True, omega=np.ones(1))
        except BaseException as e:
            errors.append(e)

    def builder() -> None:
        try:
            for k in range(200):
                try:
                    m.point(0, 1, float(k), 0.0)
                except LinkageError:
                    pass  # the mechanism is full: expected
                len(m)
                m.describe()
                m.constructions()
        except BaseException as e:
            errors.append(e)

    threads = [threading.Thread(target=f) for f in (sweeper, builder, sweeper, builder)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, repr(errors[:3])


# Float extremes: right values or a LinkageError.


def test_program_with_overflowing_period_evaluates_at_t() -> None:
    out = _core.drive.evaluate_program(
        10.0, [1e308, 1e308], [1.0, 1.0], ["cycloidal", "cycloidal"], np.array([0.5e308, 1.5e308])
    )
    assert out[:, 0] == pytest.approx([10.5, 11.5], abs=1e-12)


def test_input_range_at_float_extremes_matches_unit_scale() -> None:
    def evans_b(s: float) -> _core.FourBar:
        return _core.FourBar((0, 0), (23.05 * s, 0), 10 * s, 12 * s, 11.67 * s, (15 * s, 0), "open")

    lo, hi = evans_b(1.0).input_range()  # type: ignore[misc]
    for s in (1e300, 1e306, 1e-300):
        lo_s, hi_s = evans_b(s).input_range()  # type: ignore[misc]
        assert (lo_s, hi_s) == pytest.approx((lo, hi), abs=1e-12)
        assert evans_b(s).grashof() == evans_b(1.0).grashof()


def test_forces_reaction_columns_do_not_depend_on_valid_samples() -> None:
    fb = _hoecken()
    m = fb.mechanism()
    inertia = [(0.0, 0.0, 0.0, 0.0)] + [(1.0, 0.0, 0.0, 1.0)] * 3
    theta = np.array([0.0, 1.0])
    ok = _core.kinetostatics.forces(m, theta, np.ones(2), np.zeros(2), inertia, (0.0, -9.81), [])
    # A crank speed of 1e308 overflows every sample: no valid one, the same columns.
    bad = _core.kinetostatics.forces(
        m, theta, np.full(2, 1e308), np.zeros(2), inertia, (0.0, -9.81), []
    )
    assert ok["reaction_links"] and bad["reaction_links"] == ok["reaction_links"]
    assert bad["reactions"].shape == ok["reactions"].shape


def test_wrong_tuple_lengths_are_linkage_errors() -> None:
    # pyo3 reports these as a bare ValueError; the extension turns them into LinkageError.
    with pytest.raises(LinkageError, match="length 2"):
        _core.drive.compound_gear_train([(1, 2, 3)])  # type: ignore[list-item]
    with pytest.raises(LinkageError, match="length 2"):
        _core.FourBar((0, 0, 0), (1, 0), 1, 1, 1, (0, 0), "open")  # type: ignore[arg-type]
    m = _hoecken().mechanism()
    z = np.zeros(1)
    with pytest.raises(LinkageError, match="length 4"):
        _core.kinetostatics.forces(m, z, z, z, [(1.0, 0.0)], (0.0, 0.0), [])  # type: ignore[list-item]


def test_threads_the_system_refuses_are_swept_on_the_calling_thread() -> None:
    # Room for a few dozen 2 MiB thread stacks only: most of the 256 threads cannot start, and
    # their chunks must still be swept (the same bits as one thread), not panic.
    child = _run_limited(
        """
        import numpy as np, resource
        from linkage import _core
        fb = _core.FourBar((0, 0), (20, 0), 10, 25, 25, (50, 0), "open")
        ref = fb.uniform_sweep(0.3, 1e-4, 100_000, threads=1)
        vm = int(open("/proc/self/status").read().split("VmSize:")[1].split()[0]) * 1024
        resource.setrlimit(resource.RLIMIT_AS, (vm + (64 << 20), vm + (64 << 20)))
        many = fb.uniform_sweep(0.3, 1e-4, 100_000, threads=256)
        print("same" if np.array_equal(ref, many, equal_nan=True) else "different")
        """,
        limit_bytes=8 << 30,
    )
    assert child.returncode == 0, child.stderr[-2000:]
    assert child.stdout.strip() == "same", child.stdout + child.stderr


def test_a_circuit_that_never_assembles_names_joint_b_and_its_gap() -> None:
    # A new user's trial: the slider-crank's gap had been NaN, the four-bar's "9.4e1", both
    # "joint 3".
    import linkage

    cases = [
        (linkage.FourBar(ground=100, crank=1, coupler=2, rocker=3, point=(5, 0)), "94.0"),
        (linkage.SliderCrank(crank=10, coupler=3, offset=60, point=(12, 9)), "47.0"),
    ]
    for obj, gap in cases:
        with pytest.raises(linkage.AssemblyError) as info:
            obj.circuit(11)
        assert str(info.value) == (
            f"joint B cannot be assembled: the lengths miss closure by {gap}"
        ), str(info.value)


def test_bad_values_a_trial_found_accepted_are_errors() -> None:
    import linkage
    from linkage.cam import leg_lift

    with pytest.raises(LinkageError, match=r"target_size takes finite points, got \[nan, 0.0\]"):
        linkage.synthesis.target_size(np.array([[np.nan, 0.0], [1.0, 1.0]]))
    with pytest.raises(LinkageError, match=r"height must be a lift of 0 or more, got -1\.0"):
        leg_lift(-1.0)
    with pytest.raises(TypeError, match="height must be a real number"):
        leg_lift("tall")  # type: ignore[arg-type]
    # Three identical poses: they coincide (asking for circle points would not help).
    with pytest.raises(LinkageError, match="precision positions 0 and 1 coincide"):
        linkage.synthesis.motion(np.zeros((3, 3)))
