"""Fitting placed linkages to a target.

Their errors and residuals evaluated in the core, least squares (MINPACK, and Levenberg-Marquardt
with geodesic acceleration for the long fits), re-placing along a curve, then measuring and
checking every fit (:func:`_finish`).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, cast

import numpy as np
from numpy.typing import NDArray

from linkage import _core
from linkage._core import LinkageError
from linkage.kinematics.fourbar import FourBar
from linkage.kinematics.slider_crank import SliderCrank
from linkage.synthesis.candidates import (
    NEAR,
    Candidate,
    _apart,
    _cognates,
    _crossed,
    _forms,
    _linkage_of,
    _longest,
    _same_pivots,
    _turned,
    largest_distance,
)
from linkage.synthesis.kinds import _KIND, FOURBAR, SLIDER, Float2D, _Kind
from linkage.synthesis.targets import target_size

__all__ = [
    "GUARD",
    "LATER_EVALUATIONS",
    "LATER_POINTS",
    "SHORTEST_LINK",
    "STALL",
    "STALL_WINDOW",
]


def _placed(
    entry: NDArray[np.float64],
    frame_t: NDArray[np.float64],
    frame_c: NDArray[np.float64],
    flip: bool,
    kind: _Kind = FOURBAR,
) -> NDArray[np.float64]:
    """Move an atlas entry's linkage by the similarity taking its curve's frame onto the target's.

    The frames are the curves' normalisation frames; ``flip`` takes the other end of the major axis
    (``linkage_core::place_entry``, ``place_slider_entry``).
    """
    place = _core.synthesis.place_entry if kind is FOURBAR else _core.synthesis.place_slider_entry
    return place(
        np.ascontiguousarray(entry, dtype=np.float64),
        np.ascontiguousarray(frame_c, dtype=np.float64),
        np.ascontiguousarray(frame_t, dtype=np.float64),
        flip,
    )


def _errors(
    params: Float2D,
    crossed: NDArray[np.bool_],
    target: Float2D,
    closed: bool,
    *,
    samples: int = 256,
    exact: bool = False,
    threads: int = 1,
    kind: _Kind = FOURBAR,
) -> tuple[Float2D, Float2D]:
    p = np.ascontiguousarray(params, dtype=np.float64)
    if kind is SLIDER:
        return _core.synthesis.slider_path_errors(
            p, target, samples=samples, exact=exact, closed=closed, threads=threads
        )
    return _core.synthesis.path_errors(
        p,
        np.ascontiguousarray(crossed, dtype=bool),
        target,
        samples=samples,
        exact=exact,
        closed=closed,
        threads=threads,
    )


def _residuals(
    kind: _Kind, params: Float2D, crossed: NDArray[np.bool_], target: Float2D, s: Float2D
) -> NDArray[np.float64]:
    """``P_i(s_ij) − target_j`` of placed linkages of ``kind`` (``(M, n, 2)``, NaN unassembled)."""
    p = np.ascontiguousarray(params, dtype=np.float64)
    s = np.ascontiguousarray(s, dtype=np.float64)
    if kind is SLIDER:
        return _core.synthesis.slider_residuals(p, target, s)
    return _core.synthesis.residuals(p, np.ascontiguousarray(crossed, dtype=bool), target, s)


def _refine(
    x0: NDArray[np.float64],
    crossed: bool,
    target: Float2D,
    s0: NDArray[np.float64],
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    max_nfev: int,
    kind: _Kind = FOURBAR,
    geodesic: bool = False,
    budget: _Budget | None = None,
) -> NDArray[np.float64]:
    """Fit the true point-to-curve distance by least squares.

    The unknowns are the placed parameters (nine of a four-bar, eight of a slider-crank) and
    each target point's circuit parameter, the residuals ``P(s_i) − t_i`` evaluated in Rust.
    ``geodesic`` (the long fits of open targets) starts with :func:`_geodesic_lm` where only the
    lengths' positivity bounds the fit, then finishes with MINPACK's Levenberg-Marquardt.
    Every residual evaluation is charged to ``budget`` (when given).
    """
    # scipy.optimize costs ~0.3 s to import: only when a fit runs.
    from scipy.optimize import least_squares  # type: ignore[import-untyped]  # noqa: PLC0415

    n = len(target)
    q = kind.params
    penalty = 10.0 * size
    # Length steps scale with the target; an angle's (the slider's line) is in radians. The
    # long fits take fourth-order differences (see jac) at steps near ε^(1/5).
    h = 3e-4 if geodesic else 1e-6
    steps = np.full(q + 1, h * size)
    steps[[*kind.angles, q]] = h

    def batch(rows: NDArray[np.float64]) -> NDArray[np.float64]:
        m = len(rows)
        if budget is not None:
            budget.spent += m
        r = _residuals(kind, rows[:, :q], np.full(m, crossed), target, rows[:, q:]).reshape(m, -1)
        out: NDArray[np.float64] = np.where(np.isfinite(r), r, penalty)
        return out

    def fun(x: NDArray[np.float64]) -> NDArray[np.float64]:
        out: NDArray[np.float64] = batch(x[None, :])[0]
        return out

    def jac(x: NDArray[np.float64]) -> NDArray[np.float64]:
        return _difference_jacobian(batch, x, steps, q, n, geodesic)

    lo = np.concatenate([bounds[0], np.full(n, -np.inf)])
    hi = np.concatenate([bounds[1], np.full(n, np.inf)])
    x = np.concatenate([np.clip(x0, bounds[0] + 1e-12 * size, bounds[1] - 1e-12 * size), s0])
    # MINPACK's Levenberg-Marquardt when only the lengths' positivity bounds the fit (a
    # non-positive length gives the penalty residual); the bounded trust region with an
    # iterative solver otherwise. Neither calls a multithreaded LAPACK factorisation, which
    # oversubscribed a shared machine's cores by 50x in a measured run.
    common: dict[str, Any] = dict(
        jac=jac, x_scale="jac", ftol=1e-15, xtol=1e-15, gtol=1e-15, max_nfev=max_nfev
    )
    # A parameter bounded on both sides (by `lengths` or `pivots`) is x = lo + w(1 + sin u)/2
    # in an unbounded u (w = hi − lo), so MINPACK fits it too (the bounded trust region's
    # iterative solver had taken 7-10x as long: 150 s where 20 s was measured, #12). Every
    # other parameter is free but for the lengths' positivity (the penalty residual).
    two = np.flatnonzero(np.isfinite(lo[:q]) & np.isfinite(hi[:q]))
    one = [i for i in range(q) if i not in two]
    positive = [i for i in one if i in kind.lengths]
    free = [i for i in one if i not in kind.lengths]
    # MINPACK needs a residual per unknown (2n ≥ q + n): fewer than q points (a short arc of
    # 5 … 8) leave the fit underdetermined, which only the trust region solves (MINPACK's
    # refusal had left such targets unrefined, at 1e-2 of their size).
    if (
        n >= q
        and np.all(np.isinf(lo[free]))
        and np.all(np.isinf(hi[one]))
        and np.all(lo[positive] < 1e-6 * size)
    ):
        if len(two):
            base, w = lo[two], hi[two] - lo[two]
            # Starts a thousandth of the range inside: at a bound, u's column is zero.
            inner = np.clip(x[two], base + 1e-3 * w, base + (1 - 1e-3) * w)
            x[two] = np.arcsin(2 * (inner - base) / w - 1)
            fun_x, jac_x = fun, jac

            def placed(u: NDArray[np.float64]) -> NDArray[np.float64]:
                v = u.copy()
                v[two] = np.clip(base + w * (1 + np.sin(u[two])) / 2, lo[two], hi[two])
                return v

            def fun(x: NDArray[np.float64]) -> NDArray[np.float64]:
                return fun_x(placed(x))

            def jac(x: NDArray[np.float64]) -> NDArray[np.float64]:
                j = jac_x(placed(x))
                j[:, two] *= w * np.cos(x[two]) / 2
                return j

        if geodesic:
            # Geodesic steps down the valley, then MINPACK's (a fifth as many evaluations more)
            # for the last digits, which its convergence near the answer gives sooner.
            x = _geodesic_lm(fun, jac, x, max_nfev, q)
            common["max_nfev"] = max_nfev // 5

        # SciPy's C MINPACK (1.15 on) reads one element past its copy of the Jacobian when it
        # recomputes the norm of the last column of its pivoted QR: what lies there changes
        # from call to call, and with it a few fits, so one search returned other candidates
        # run to run (valgrind: "Invalid read of size 8 … 0 bytes after a block" in qrfac). So
        # a last unknown y joins, with one residual GUARD·y of its own: its column, the
        # smallest that is not zero, is pivoted after every other but zero ones, no other
        # column's reflection touches it, so its norm is never recomputed (nor is a zero
        # column's), and nothing past the Jacobian is read. The fit keeps full rank and its
        # steps (a column of zeros instead had cost the last digits: 4e-10 of the size where
        # 3e-14 had been reached).
        def fun_g(y: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.append(fun(y[:-1]), GUARD * y[-1])

        def jac_g(y: NDArray[np.float64]) -> NDArray[np.float64]:
            j = jac(y[:-1])
            out = np.zeros((j.shape[0] + 1, j.shape[1] + 1))
            out[:-1, :-1] = j
            out[-1, -1] = GUARD
            return out

        common["jac"] = jac_g
        res = least_squares(fun_g, np.append(x, 0.0), method="lm", **common)
        if len(two):
            res.x[two] = np.clip(base + w * (1 + np.sin(res.x[two])) / 2, lo[two], hi[two])
    else:
        res = least_squares(fun, x, bounds=(lo, hi), method="trf", tr_solver="lsmr", **common)
    out: NDArray[np.float64] = res.x[:q]
    return out


def _difference_jacobian(
    batch: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    x: NDArray[np.float64],
    steps: NDArray[np.float64],
    q: int,
    n: int,
    geodesic: bool,
) -> NDArray[np.float64]:
    """Return the Jacobian at ``x`` of :func:`_refine`'s residuals by differences (``batch``).

    ``q`` placed parameters, then ``n`` circuit parameters (one per target point); ``steps``
    holds the ``q`` parameters' steps, then the circuit parameters' one step.
    """
    # Central differences of all q + 1 directions (the q parameters, then every s at once:
    # s_i moves residual i only) in one batched call. The long fits take the fourth-order
    # stencil (8(r(x+h) − r(x−h)) − (r(x+2h) − r(x−2h)))/12h, error O(h⁴) + O(ε/h), about
    # 1e-12 of the Jacobian's scale at h = 3e-4, where the central O(h²) + O(ε/h) at
    # h = 1e-6 is about 2e-10: the long fits' scaled Jacobians span singular values of
    # 10⁷ … 10⁹, and the directions along the valley are the small ones. Two arcs of
    # `bench/open_arcs.py --seed 2` are recovered only so (docs/synthesis.md); the first
    # fits keep the central differences (half the evaluations a Jacobian).
    d = np.zeros((q + 1, q + n))
    d[np.arange(q), np.arange(q)] = steps[:q]
    d[q, q:] = steps[q]
    m = q + 1
    if geodesic:
        r = batch(np.concatenate([x + d, x - d, x + 2 * d, x - 2 * d]))
        g = (8 * (r[:m] - r[m : 2 * m]) - (r[2 * m : 3 * m] - r[3 * m :])) / (12 * steps[:, None])
    else:
        r = batch(np.concatenate([x + d, x - d]))
        g = (r[:m] - r[m:]) / (2 * steps[:, None])
    j = np.zeros((2 * n, q + n))
    j[:, :q] = g[:q].T
    rows = np.arange(n)
    j[2 * rows, q + rows] = g[q, 0::2]
    j[2 * rows + 1, q + rows] = g[q, 1::2]
    return j


SHORTEST_LINK = 1e-6
"""The shortest link a candidate may have, in target sizes (:data:`EXACT`: a link shorter
than the error a fit is exact to is no link)."""

GUARD = 1e-100
"""The weight of the guard unknown that keeps SciPy's MINPACK inside its Jacobian (:func:`_refine`):
far below any column of a fit's Jacobian, far above the smallest normal number when squared."""


STALL_WINDOW = 100
"""Evaluations over which a long fit (:func:`_geodesic_lm`) must lower its sum of squares by
:data:`STALL`, or stop."""

STALL = 1e-3
"""Least relative decrease of a long fit's sum of squares over :data:`STALL_WINDOW` evaluations.
A fit crawling down a valley to an exact linkage lowers it by far more: random#6 of
``bench/open_arcs.py`` from 1.4e-5 to 1.6e-6 of the size in 1,500 evaluations, a factor of 76
in the sum, 1.3 a window on average."""


def _geodesic_lm(
    fun: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    jac: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    x0: NDArray[np.float64],
    max_nfev: int,
    dense: int | None = None,
) -> NDArray[np.float64]:
    """Minimise ``|fun(x)|²`` by Levenberg-Marquardt with geodesic acceleration.

    Transtrum and Sethna, "Improvements to the Levenberg-Marquardt algorithm for nonlinear
    least-squares minimization" (arXiv:1201.5885, 2012), section 3. In variables scaled by
    ``D = diag(max over iterations of |J_k|²)^½`` (MINPACK's scaling), each iteration solves
    ``(JᵀJ + λD²) v = −Jᵀr`` for the velocity, estimates the second directional derivative
    ``r_vv ≈ (2/h)((r(x + hv) − r(x))/h − Jv)`` (``h = 0.1``), solves
    ``(JᵀJ + λD²) a = −Jᵀr_vv`` for the acceleration and tries ``x + v + a/2`` when
    ``|Da| ≤ 0.75 |Dv|``; both solves by one QR factorisation of ``[J D⁻¹; √λ I]``
    (:func:`_damped_solver`: of its first ``dense`` columns, those of ``J`` that are dense, and
    a reflection of each point's rows; ``None``: all). An accepted
    step divides ``λ`` by 3, a rejected one multiplies it by ``ν`` (2, doubling while rejections
    go on; Nielsen's rule). It stops after ``max_nfev`` evaluations of ``fun`` (two an
    iteration), when a step is below 1e-15 of ``|Dx|``, when ``λ`` reaches 1e30 (no step
    lowers the sum: a minimum to rounding), or when :data:`STALL_WINDOW` evaluations lowered the
    sum by less than the fraction :data:`STALL` of it (a fit of points no linkage draws creeps
    on by hairs: 36 long fits of 1,500 evaluations had taken 48 s of a 75 s search of 100 random
    points, #29).

    The acceleration bends each step along the curved, narrow valley of near-fits that a
    short arc's fit follows (the scaled Jacobian's singular values span 10⁷ … 10⁹), where
    MINPACK's straight steps crawl: from a long fit's start on 0.18 of a triple-rocker's
    circuit (1.4e-5 of the size), one round of MINPACK ended at 2.1e-5 after 5,000
    evaluations, this at 1.6e-6 after 1,500 (docs/synthesis.md).
    """
    x = np.array(x0, dtype=np.float64)
    r = fun(x)
    cost = float(r @ r)
    j = jac(x)
    nfev, m = 1, len(x)
    d2 = np.zeros(m)
    lam, nu = 1e-3, 2.0
    # The sum of squares at the start of the current window of STALL_WINDOW evaluations.
    mark_nfev, mark_cost = nfev, cost
    while nfev < max_nfev:
        if nfev - mark_nfev >= STALL_WINDOW:
            if cost > (1.0 - STALL) * mark_cost:
                break  # stalled: a window of evaluations lowered the sum by less than STALL
            mark_nfev, mark_cost = nfev, cost
        d2 = np.maximum(d2, np.sum(j * j, axis=0))
        d = np.sqrt(np.maximum(d2, 1e-300))
        solve = _damped_solver(j / d, lam, m if dense is None else dense)
        vy = solve(r)
        v = vy / d
        r_h = fun(x + 0.1 * v)
        nfev += 1
        ay = solve((2.0 / 0.1) * ((r_h - r) / 0.1 - j @ v))
        new_cost = math.inf
        if np.linalg.norm(ay) <= 0.75 * np.linalg.norm(vy):
            x_new = x + v + 0.5 * ay / d
            r_new = fun(x_new)
            nfev += 1
            new_cost = float(r_new @ r_new)
        if new_cost < cost:
            x, r, cost = x_new, r_new, new_cost
            j = jac(x)
            lam, nu = max(lam / 3.0, 1e-30), 2.0
            if np.linalg.norm(vy) < 1e-15 * (np.linalg.norm(d * x) + 1e-15):
                break
        else:
            lam, nu = min(lam * nu, 1e30), min(2.0 * nu, 1e3)
            if lam >= 1e30:
                break
    return x


def _damped_solver(
    js: NDArray[np.float64], lam: float, q: int
) -> Callable[[NDArray[np.float64]], NDArray[np.float64]]:
    """Return the solver of ``min |[J; √λ I] y + [b; 0]|`` for right-hand sides ``b``.

    ``J`` (``js``, ``2n × (q + n)``) is a fit's scaled Jacobian: ``q`` dense columns, then one
    column per target point ``i`` whose only entries are in rows ``2i`` and ``2i + 1`` (its
    circuit parameter moves its residual alone). A Householder reflection of each point's three
    rows (its two, and its damping row ``√λ`` in column ``q + i``) leaves that column one entry
    (Golub and Van Loan, *Matrix Computations*, 4th ed., 5.1.2), and a QR of the remaining
    ``(2n + q) × q`` rows solves the dense part, then each point's parameter by substitution:
    orthogonal steps, as a QR of the whole ``(3n + q) × (q + n)`` matrix, in ``O(n q²)`` where
    that takes ``O(n³)`` (the whole QR of 100 points took 2-13 ms, most of a long fit, and
    more threads than a loaded machine had, #29).
    """
    n = js.shape[1] - q
    root = math.sqrt(lam)
    if n == 0:
        # Every column dense: one QR of the (2n + m) × m matrix.
        q0, r0 = np.linalg.qr(np.vstack([js, root * np.eye(q)]))
        qt0 = q0[: len(js)].T

        def solve_dense(b: NDArray[np.float64]) -> NDArray[np.float64]:
            out: NDArray[np.float64] = np.linalg.solve(r0, -(qt0 @ b))
            return out

        return solve_dense
    a = js[:, :q]
    w = np.column_stack(
        [
            js[2 * np.arange(n), q + np.arange(n)],
            js[2 * np.arange(n) + 1, q + np.arange(n)],
            np.full(n, root),
        ]
    )
    sigma = np.linalg.norm(w, axis=1)
    alpha = -np.copysign(sigma, w[:, 0])  # H w = alpha e₁, no cancellation in u₀
    u = w.copy()
    u[:, 0] -= alpha
    beta = 2.0 / np.einsum("ij,ij->i", u, u)  # u ≠ 0: |u₀| ≥ σ ≥ √λ > 0

    def reflect(rows: NDArray[np.float64]) -> NDArray[np.float64]:
        """Apply each point's reflection to its three rows (``(n, 3, ...)``)."""
        c = beta.reshape((n,) + (1,) * (rows.ndim - 2)) * np.einsum("ij,ij...->i...", u, rows)
        out: NDArray[np.float64] = rows - u.reshape(u.shape + (1,) * (rows.ndim - 2)) * c[:, None]
        return out

    blocks = np.zeros((n, 3, q))
    blocks[:, 0], blocks[:, 1] = a[0::2], a[1::2]
    hb = reflect(blocks)
    pivot = hb[:, 0]
    qq, rr = np.linalg.qr(np.vstack([hb[:, 1:].reshape(2 * n, q), root * np.eye(q)]))
    qt = qq[: 2 * n].T

    def solve(b: NDArray[np.float64]) -> NDArray[np.float64]:
        rows = np.zeros((n, 3))
        rows[:, 0], rows[:, 1] = b[0::2], b[1::2]
        hr = reflect(rows)
        yp = np.linalg.solve(rr, -(qt @ hr[:, 1:].reshape(2 * n)))
        ys = -(hr[:, 0] + pivot @ yp) / alpha
        return np.concatenate([yp, ys])

    return solve


def _arc(feet: NDArray[np.float64], closed: bool) -> tuple[float, float]:
    """Return the circuit-parameter arc that holds every foot.

    The whole circuit for a closed target, else the complement of the largest gap between feet
    (``linkage_core::covering_arc``).
    """
    if closed:
        return (0.0, 2 * math.pi)
    arc = _core.synthesis.covering_arc(np.ascontiguousarray(feet, dtype=np.float64))
    return arc if arc is not None else (math.nan, math.nan)


LATER_EVALUATIONS = 1_000_000
"""Residual evaluations (of one placed linkage on every point: a Jacobian by differences takes
``2(q + 1)`` or ``4(q + 1)``) the later stages of an open search of up to
:data:`LATER_POINTS` points may spend (:class:`_Budget`). ``bench/open_arcs.py`` with seeds 0
and 1: the arcs those stages recovered spent at most 348,370 (seed 1 random#33), the two misses
616,866 and 886,645."""

LATER_POINTS = 40
"""Points of an open target up to which its later stages have all of :data:`LATER_EVALUATIONS`;
beyond, ``(LATER_POINTS / n)²`` of them."""


@dataclass
class _Budget:
    """The residual evaluations the later stages of an open search may spend, and spent.

    The later stages: long fits, wider and re-placed matches, restarts; :attr:`out` once spent.

    Those stages run on a target no linkage draws, each fit to its end, and an evaluation's
    cost, with the linear algebra of the fit, grows with the points: 100 random points had taken
    75-125 s, 23,928 QR factorisations (#29). With ``(LATER_POINTS / n)²`` of the evaluations
    for ``n`` points the time grows about as ``n``; a target of up to :data:`LATER_POINTS` (the
    40 of ``bench/open_arcs.py``) keeps them all. A stage checks it between fits: the last fit
    may overrun it by one fit's evaluations.
    """

    left: float
    spent: int = 0

    @classmethod
    def of(cls, points: int) -> _Budget:
        """Return the budget of a target of ``points`` points."""
        return cls(LATER_EVALUATIONS * min(1.0, (LATER_POINTS / max(points, 1)) ** 3))

    @property
    def out(self) -> bool:
        """Whether it is spent."""
        return self.spent >= self.left


_Budget.__module__ = "linkage.synthesis"  # as before the split: pickles and reprs name it so


def _slid_along_curves(
    kind: _Kind,
    params: NDArray[np.float64],
    crossed: NDArray[np.bool_],
    target: Float2D,
    rounds: int,
    threads: int,
) -> NDArray[np.float64]:
    """Move each placed linkage (rows of ``params``) along its curve onto an open ``target``.

    Each of ``rounds`` rounds (iterative closest points with a similarity) takes every target
    point's nearest point of the linkage's curve (its foot) and the least-squares similarity
    ``z ↦ a·z + b`` (complex ``a``, ``b``; Procrustes, no reflection) from the feet to the
    target points, and moves the linkage by it: its pivots mapped, its lengths scaled by
    ``|a|``, a slider's line turned by ``arg a``. An arc match is placed by the frames of its
    stored arc and of the target, which rarely start and end at the same places of the
    circuit: the target then sits askew along the curve, and its distance can rank a match of
    the right shape below others (docs/synthesis.md, step 4). Rows whose curve does not
    assemble at every foot stay where they are.
    """
    p = np.array(params, dtype=np.float64)
    t = target[:, 0] + 1j * target[:, 1]
    tm = t.mean()
    scaled = list(kind.scaled)
    for _ in range(rounds):
        _, feet = _errors(p, crossed, target, False, threads=threads, kind=kind)
        rows = np.flatnonzero(np.all(np.isfinite(feet), axis=1))
        if not len(rows):
            break
        r = _residuals(kind, p[rows], crossed[rows], target, feet[rows])
        z = (r[..., 0] + target[:, 0]) + 1j * (r[..., 1] + target[:, 1])
        zm = z.mean(axis=1)
        spread = np.sum(np.abs(z - zm[:, None]) ** 2, axis=1)
        ok = np.all(np.isfinite(z), axis=1) & (spread > 0)
        rows, z, zm, spread = rows[ok], z[ok], zm[ok], spread[ok]
        a = np.sum((t - tm)[None, :] * np.conj(z - zm[:, None]), axis=1) / spread
        b = tm - a * zm
        q = p[rows]
        for i, j in kind.pivots:
            w = (q[:, i] + 1j * q[:, j]) * a + b
            q[:, i], q[:, j] = w.real, w.imag
        q[:, scaled] *= np.abs(a)[:, None]
        for i in kind.angles:
            q[:, i] += np.angle(a)
        p[rows] = q
    return p


def _matched_curve(c: Candidate[Any], target: Float2D, closed: bool, samples: int = 512) -> Float2D:
    """Sample the part of ``c``'s circuit that the target points fall on (closed: all of it)."""
    kind = _KIND[c.kind]
    crossed = np.array([_crossed(c)])
    _, feet = _errors(
        c.params[None, :], crossed, target, closed, samples=2048, exact=True, kind=kind
    )
    lo, hi = _arc(feet[0], closed)
    s = np.linspace(lo, hi, samples)[None, :]
    # Residuals from the origin are the curve points themselves.
    pts = _residuals(kind, c.params[None, :], crossed, np.zeros((samples, 2)), s)
    return np.ascontiguousarray(pts[0])


def _distinct(
    ranked: list[Candidate[Any]], target: Float2D, closed: bool, size: float, top: int
) -> list[Candidate[Any]]:
    """Return the first ``top`` of ``ranked`` drawing different curves (cognates kept).

    Two candidates draw the same curve when each one's matched part lies within
    ``max(1e-6 size, error / 20)`` of the other's (a difference the target cannot tell); the
    later (worse-ranked) one is dropped unless it is a Roberts cognate of the earlier. Two
    candidates of the same kind and assembly whose parameters agree to :data:`NEAR` of the
    larger of the size and the shorter of their longest links (a slider line's direction to
    :data:`NEAR` radians) are one design, whatever their matched
    curves (one that does not sample finitely included): a near-copy the optimiser left in the
    same valley. So are two four-bars that are one linkage driven at either pivot (the better
    drive is kept), and two rocking slider-cranks that are one linkage with its line reversed.
    """
    kept: list[tuple[Candidate[Any], Float2D, list[tuple[Any, NDArray[np.float64]]]]] = []
    for c in ranked:
        if len(kept) >= top:
            break
        curve = _matched_curve(c, target, closed)
        same = False
        for u, ucurve, forms in kept:
            tol = max(1e-6 * size, min(c.error, u.error) / 20)
            # Near-copies are judged on the scale of the drawing that shows the whole linkage.
            near = max(size, min(_longest(c), _longest(u)))
            if any(
                type(form) is type(c.linkage)
                and getattr(form, "assembly", None) == getattr(c.linkage, "assembly", None)
                and params.shape == c.params.shape
                and _apart(params, c.params, _KIND[c.kind], near) <= NEAR * near
                for form, params in forms
            ):
                same = True
                break
            if (
                largest_distance(curve, ucurve) <= tol
                and largest_distance(ucurve, curve) <= tol
                and (
                    _same_pivots(u, c, 1e-9 * size)
                    or not _cognates(u, c, max(1e-6 * size, 1e-3 * size))
                )
            ):
                same = True
                break
        if not same:
            kept.append((c, curve, _forms(c)))
    return [c for c, _, _ in kept]


def _bounds(
    lengths: tuple[float, float] | None,
    pivots: tuple[tuple[float, float], tuple[float, float]] | None,
    size: float,
    kind: _Kind = FOURBAR,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    lo = np.full(kind.params, -np.inf)
    hi = np.full(kind.params, np.inf)
    at = list(kind.lengths)
    lo[at] = 1e-9 * size
    if lengths is not None:
        a, b = float(lengths[0]), float(lengths[1])
        if not (0 < a < b):
            raise LinkageError(
                f"lengths must be (least, greatest) with 0 < least < greatest, got {lengths}"
            )
        lo[at], hi[at] = a, b
        # The coupler point within the greatest length of both its joints (see _failed).
        point = [kind.params - 2, kind.params - 1]
        lo[point], hi[point] = -b, b
    if pivots is not None:
        (x0, y0), (x1, y1) = pivots
        if not (x0 < x1 and y0 < y1):
            raise LinkageError(f"pivots must be ((xmin, ymin), (xmax, ymax)), got {pivots}")
        for ix, iy in kind.pivots:
            lo[ix], hi[ix] = x0, x1
            lo[iy], hi[iy] = y0, y1
    return lo, hi


def _finish(
    pool: list[tuple[NDArray[np.float64], bool, str]],
    target: Float2D,
    closed: bool,
    size: float,
    bounds: tuple[NDArray[np.float64], NDArray[np.float64]],
    refine: int,
    threads: int,
    bar: Any,
    enough: int | None = None,
    kind: _Kind = FOURBAR,
    admissible: Callable[[Candidate[Any]], bool] | None = None,
    nfev: int = 60,
    exact_at: float = 1e-10,
    geodesic: bool = False,
    budget: _Budget | None = None,
) -> list[Candidate[Any]]:
    """Refine the first ``refine`` of ``pool``, then measure and check every one.

    Each refinement is up to three rounds of least squares of at most ``nfev`` evaluations each
    (``geodesic``: :func:`_refine`'s).
    Stop early once ``enough`` distinct candidates that are ``admissible`` (meet the caller's
    constraints) draw the target to ``exact_at`` of its size, or once ``budget`` is spent (the
    rest of ``pool`` is left out).
    """
    out: list[Candidate[Any]] = []
    exact: list[NDArray[np.float64]] = []
    for k, (x, crossed, source) in enumerate(pool):
        if enough is not None and len(exact) >= enough:
            break
        if budget is not None and budget.out:
            break
        if k < refine:
            # Rounds of least squares, each from every target point's true nearest curve point
            # (where the curve crosses itself a first guess may put a point on the wrong pass).
            # Least squares lowers the RMS distance, which can raise the largest: the best
            # linkage by largest distance is kept too (an earlier round or the unrefined one).
            best_x, best_e = x, math.inf
            rounds = [x]
            for r in range(4):
                e, feet = _errors(
                    x[None, :],
                    np.array([crossed]),
                    target,
                    closed,
                    samples=512,
                    exact=True,
                    kind=kind,
                )
                err = float(e[0, 0]) if np.isfinite(e[0, 0]) else math.inf
                if err < best_e:
                    best_x, best_e = x, err
                if r == 3 or not np.all(np.isfinite(feet)) or err <= 1e-10 * size:
                    break
                try:
                    x = _refine(
                        x, crossed, target, feet[0], size, bounds, nfev, kind, geodesic, budget
                    )
                except (ValueError, LinkageError):
                    break
                rounds.append(x)
            if bar is not None:
                bar.update(1)
            # The last refinement, and the best by largest distance when that is another (an
            # earlier round or the unrefined one): both are measured, the ranking decides.
            tries = [x] + ([best_x] if best_x is not x else [])
        else:
            tries, rounds = [x], []
        measured = [_measure(xt, crossed, target, closed, source, threads, kind) for xt in tries]
        if admissible is not None and not any(c is not None and admissible(c) for c in measured):
            # Least squares minds the fit, not the constraints: when it left what they admit,
            # the last round (or the start) that they admit is kept too.
            for xr in reversed(rounds):
                if any(xr is xt for xt in tries):
                    continue
                c = _measure(xr, crossed, target, closed, source, threads, kind)
                if c is not None and admissible(c):
                    measured.append(c)
                    break
        for cand in measured:
            if cand is not None:
                out.append(cand)
                if (
                    cand.error <= exact_at * size
                    and (admissible is None or admissible(cand))
                    and all(np.max(np.abs(cand.params - e)) > 1e-6 * size for e in exact)
                ):
                    exact.append(cand.params)
    return out


def _measure(
    x: NDArray[np.float64],
    crossed: bool,
    target: Float2D,
    closed: bool,
    source: str,
    threads: int,
    kind: _Kind = FOURBAR,
) -> Candidate[Any] | None:
    """Measure and check a candidate.

    ``None`` when its circuit does not assemble throughout or the tracker leaves it, or when a
    link is shorter than :data:`SHORTEST_LINK` of the target's size (a crank of 4e-6 mm on a
    60 mm foot path had been listed as a full-turn crank-rocker drawing a dot).
    """
    links = list(x[list(kind.lengths)])
    if kind is FOURBAR:
        links.append(math.hypot(x[2] - x[0], x[3] - x[1]))  # the ground
    if min(links) < SHORTEST_LINK * target_size(target):
        return None
    e, feet = _errors(
        x[None, :], np.array([crossed]), target, closed, samples=2048, exact=True, kind=kind
    )
    if not np.all(np.isfinite(e[:, :2])):  # (back is NaN for an open target)
        return None
    lo_s, hi_s = _arc(feet[0], closed)
    fb: FourBar | SliderCrank
    try:
        if kind is SLIDER:
            # The line's direction as fitted may have turned past a full turn: the same
            # linkage, reported with its angle in [-π, π] (so are its crank range and scene).
            x = x.copy()
            x[2] = math.remainder(float(x[2]), 2 * math.pi)
            problem, full, th_lo, th_hi, mu, through = _core.synthesis.slider_circuit_info(
                x, lo_s, hi_s
            )
            fb = _linkage_of(x, crossed, kind)
            grashof = "crank-slider" if full else "rocker-slider"
        else:
            problem, full, th_lo, th_hi, mu, through = _core.synthesis.circuit_info(
                x, crossed, lo_s, hi_s
            )
            fb = _linkage_of(x, crossed, kind)
            grashof = cast(FourBar, fb).grashof()
        if problem is None and full and not closed:
            # A crank that turns fully is driven through the whole turn, not only the matched
            # part: its transmission angle counts over the turn (a candidate that read 53.5°
            # on its matched part came within 0.1° of a toggle elsewhere).
            whole = (
                _core.synthesis.slider_circuit_info(x, 0.0, 2 * math.pi, check_samples=2)
                if kind is SLIDER
                else _core.synthesis.circuit_info(x, crossed, 0.0, 2 * math.pi, check_samples=2)
            )
            mu = min(mu, whole[4])
    except LinkageError:
        return None
    if problem is not None:
        return None
    return Candidate(
        linkage=fb,
        error=float(e[0, 0]),
        rms=float(e[0, 1]),
        back=float(e[0, 2]),
        crank_range=_turned(th_lo, th_hi),
        full_turn=full,
        grashof=grashof,
        min_transmission=mu,
        through_limit=through,
        source=source,
        params=x.copy(),
        kind=kind.name,
    )
