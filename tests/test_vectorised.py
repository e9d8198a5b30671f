"""Vectorised sweeps equal per-sample solves (hypothesis), and the GIL is released."""

from __future__ import annotations

import threading
import time

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import linkage

angles = st.lists(st.floats(-50, 50, allow_nan=False), min_size=1, max_size=60)


@settings(max_examples=200, deadline=None)
@given(theta=angles)
def test_vectorised_equals_per_sample_for_crank_rocker(theta):
    fb = linkage.catalog.hoecken()
    s = fb.sweep(theta, omega=2.0, outputs=("velocity",))
    for i, t in enumerate(theta):
        one = fb.sweep(t, omega=2.0, outputs=("velocity",))
        np.testing.assert_allclose(s.joints[i], one.joints, rtol=0, atol=1e-12)
        np.testing.assert_allclose(s.velocity[i], one.velocity, rtol=0, atol=1e-10)


@settings(max_examples=100, deadline=None)
@given(theta=st.lists(st.floats(-1.4, 1.4), min_size=1, max_size=40))
def test_vectorised_equals_per_sample_for_peaucellier(theta):
    # Within |θ| ≤ 1.4 no dyad reaches its toggle, so each sample's branch is the declared one.
    m = linkage.catalog.peaucellier()
    s = m.sweep(theta)
    for i, t in enumerate(theta):
        np.testing.assert_allclose(s.joints[i], m.sweep(t).joints, rtol=0, atol=1e-12)


def test_sweep_releases_the_gil():
    fb = linkage.catalog.hoecken()
    theta = np.linspace(0, 2000 * np.pi, 3_000_000)
    # Baseline rate of a pure-Python counting loop.
    n, t0 = 0, time.perf_counter()
    while time.perf_counter() - t0 < 0.05:
        n += 1
    rate = n / (time.perf_counter() - t0)

    started, done = threading.Event(), threading.Event()
    span = {}

    def work():
        started.set()
        t = time.perf_counter()
        fb.sweep(theta)
        span["t"] = time.perf_counter() - t
        done.set()

    th = threading.Thread(target=work)
    th.start()
    started.wait()
    count = 0
    while not done.is_set():
        count += 1
    th.join()
    # With the GIL held for the whole sweep this loop could run only between switch intervals;
    # released, it runs alongside (2 cores). Require a third of the free-running count.
    expected = rate * span["t"]
    assert span["t"] > 0.05, "sweep too short to judge"
    assert count > 0.3 * expected, (count, expected)
