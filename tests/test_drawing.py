"""Drawings from the linkage's structure (linkage.drawing) and the report figures drawn from them:
the bars that exist and no others, walkers' legs at their mounts, limits from the path, legs named
by side and position, and report images that are not blank."""

from __future__ import annotations

import math

import numpy as np
import pytest
from PIL import Image

import linkage
from linkage.drawing import (
    Drawing,
    clip_to,
    mechanism_drawing,
    path_window,
    sagittal_pivots,
    walker_drawing,
)
from linkage.walker import leg_labels

THETA = np.linspace(0, 2 * np.pi, 73)


def named(d: Drawing, kind: str | None = None) -> set[frozenset[str]]:
    """The drawing's links as sets of joint names (of one kind, if given)."""
    return {
        frozenset(d.joint_names[j] for j in k.joints)
        for k in d.links
        if kind is None or k.kind == kind
    }


def edges(d: Drawing) -> set[frozenset[str]]:
    """Every pair of joints a drawn bar or plate outline connects."""
    out = set()
    for k in d.links:
        if k.kind == "ground":
            continue
        js = [d.joint_names[j] for j in k.joints]
        pairs = zip(js, js[1:] + js[:1]) if k.kind == "plate" else zip(js, js[1:])
        out |= {frozenset(p) for p in pairs}
    return out


def test_fourbar_has_its_four_links_and_no_bar_c_a():
    fb = linkage.catalog.hoecken()  # coupler point on the line A-B
    d = mechanism_drawing(fb, fb.sweep(THETA))
    assert named(d, "bar") == {
        frozenset("OA"),
        frozenset("ABP"),
        frozenset("CB"),
    }
    assert named(d, "ground") == {frozenset("OC")}
    assert [d.joint_names[j] for j in d.pivots] == ["O", "C"]
    assert frozenset("CA") not in edges(d) and frozenset("OC") not in edges(d)
    # The coupler's joints in order along it: A, B, then P beyond B.
    (coupler,) = [k for k in d.links if k.name == "coupler"]
    assert [d.joint_names[j] for j in coupler.joints] == ["A", "B", "P"]
    assert d.trace == d.joint_names.index("P")
    np.testing.assert_array_equal(d.paths["trace P"], fb.sweep(THETA).point)


def test_coupler_point_off_the_line_makes_a_plate():
    fb = linkage.FourBar(ground=20, crank=10, coupler=25, rocker=25, point=(12, 8))
    d = mechanism_drawing(fb, fb.sweep(THETA))
    assert named(d, "plate") == {frozenset("ABP")}
    assert named(d, "bar") == {frozenset("OA"), frozenset("CB")}
    assert frozenset("CA") not in edges(d)


def test_jansen_links_are_its_link_members():
    m = linkage.catalog.jansen()
    d = mechanism_drawing(m, m.sweep(THETA))
    members = m.link_members()
    assert named(d) == {frozenset(ms) for ms in members}
    assert named(d, "ground") == {frozenset(members[0])}
    assert len(named(d, "bar")) == len(members) - 1  # every moving Jansen link is binary


def test_slider_is_a_block_on_its_guide():
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("G", (0, -5))
    m.crank("A", "O", radius=10)
    m.slider("B", "A", 30, "G", direction=(2, 0))
    d = mechanism_drawing(m, m.sweep(THETA))
    (sl,) = d.sliders
    assert d.joint_names[sl.joint] == "B" and d.joint_names[sl.origin] == "G"
    np.testing.assert_allclose(sl.direction, np.tile([1.0, 0.0], (len(THETA), 1)))
    # The block joins no link of its own, and G (the guide's origin) is not a pivot.
    assert named(d, "bar") == {frozenset("OA"), frozenset("AB")}
    assert [d.joint_names[j] for j in d.pivots] == ["O"]


def test_slider_on_a_link_slides_along_the_turned_link():
    m = linkage.Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("C", (3, 0))
    m.crank("A", "O", radius=1.0)
    m.slider("S", "C", 4.0, "O", link=("O", "A"), angle=0.3)
    d = mechanism_drawing(m, m.sweep(THETA))
    (sl,) = d.sliders
    assert d.joint_names[sl.joint] == "S" and d.joint_names[sl.origin] == "O"
    # The crank O→A points at θ: the guide at θ + 0.3, sample by sample.
    phi = THETA + 0.3
    np.testing.assert_allclose(sl.direction, np.c_[np.cos(phi), np.sin(phi)], rtol=0, atol=1e-15)


def test_sweep_of_another_mechanism_is_refused():
    fb = linkage.catalog.hoecken()
    with pytest.raises(linkage.LinkageError, match="not the mechanism's"):
        mechanism_drawing(linkage.catalog.jansen(), fb.sweep(THETA))


@pytest.mark.parametrize("model", ["quadruped_hoecken", "hexapod_tripod"])
@pytest.mark.parametrize("view", ["side", "top"])
def test_walker_legs_sit_at_their_mounts(model, view):
    w = getattr(linkage.catalog, model)()
    sim = w.simulate(THETA)
    d = walker_drawing(w, sim, view)
    ax = (0, 2) if view == "side" else (0, 1)
    for li, leg in enumerate(w.legs):
        fb = leg.linkage
        assert isinstance(fb, linkage.FourBar)
        # The crank pivot O of every leg is at the leg's mount, in every sample.
        o = d.positions[:, d.joint_names.index(f"{leg.name}.O")]
        mount = np.array(leg.mount)[list(ax)]
        np.testing.assert_allclose(o, np.broadcast_to(mount, o.shape), atol=1e-12)
        # The drawn foot is the simulation's foot.
        foot = d.positions[:, d.joint_names.index(f"{leg.name}.foot")]
        np.testing.assert_allclose(foot, sim.feet[:, li][:, list(ax)], atol=1e-12)
        assert {k.leg for k in d.links if k.name.startswith(f"{leg.name}.")} == {li}
    assert d.stance is not None and d.stance.shape == sim.stance.shape
    if view == "side":
        assert d.ground == sim.ground and d.support is None
    else:
        assert d.support is not None and d.cg == tuple(w.cg)


@pytest.mark.parametrize("model", ["quadruped_hoecken", "hexapod_tripod"])
def test_sagittal_pivots_are_the_side_views_pivots(model):
    """One pose a leg gives the fixed pivots the side view marks over the whole run (the
    hexapod's legs are horizontal: none)."""
    w = getattr(linkage.catalog, model)()
    sim = w.simulate(THETA)
    d = walker_drawing(w, sim, "side")
    pins = sagittal_pivots(w, sim)
    assert len(pins) == len(d.pivots) == (8 if model == "quadruped_hoecken" else 0)
    if not len(pins):
        return
    drawn = d.positions[:, list(d.pivots)]
    np.testing.assert_allclose(pins[:, [0, 2]], drawn[0], atol=1e-12)
    np.testing.assert_allclose(drawn, np.broadcast_to(drawn[0], drawn.shape), atol=1e-12)


def test_rigid_leg_bars_keep_their_length_in_the_body_frame():
    w = linkage.catalog.quadruped_hoecken()
    d = walker_drawing(w, w.simulate(THETA), "side")
    k = next(k for k in d.links if k.name == "A.crank")
    a, b = (d.positions[:, j] for j in k.joints)
    np.testing.assert_allclose(np.hypot(*(a - b).T), w.legs[0].linkage.crank, rtol=1e-12)


def test_bounds_ignore_far_curvature_centres():
    fb = linkage.catalog.hoecken()
    s = fb.sweep(THETA, outputs=("point", "joints", "curvature"))
    c = s.curvature_centre
    assert np.nanmax(np.abs(c)) > 1e3  # the straight part puts centres far away
    d = mechanism_drawing(fb, s)
    x0, x1, y0, y1 = d.bounds()
    assert max(x1 - x0, y1 - y0) < 100  # the linkage is ~60 mm across
    w = path_window(s.point, grow=0.5)
    shown = clip_to(c, w)
    inside = np.isfinite(shown).all(axis=1)
    assert inside.any() and not inside.all()
    assert (shown[inside, 0] >= w[0]).all() and (shown[inside, 1] <= w[3]).all()


def test_leg_labels_name_side_and_position_front_to_rear():
    assert linkage.catalog.hexapod_tripod().leg_labels() == ("L1", "L2", "L3", "R1", "R2", "R3")
    assert linkage.catalog.quadruped_hoecken().leg_labels() == ("L1", "R1", "L2", "R2")
    # Order of the legs does not matter, only their mounts.
    assert leg_labels([(-1, -1, 0), (1, 1, 0), (0, 0, 0), (1, -1, 0)]) == ("R2", "L1", "M1", "R1")
    with pytest.raises(linkage.LinkageError):
        leg_labels([(0, 0)])


def test_palette_is_distinct_for_twelve_lines():
    from linkage.report import line_style

    styles = [line_style(k) for k in range(28)]
    assert len(set(styles)) == 28
    assert len({c for c, _ in styles[:14]}) == 14


def check_image(path):
    with Image.open(path) as im:
        frames = getattr(im, "n_frames", 1)
        shots = []
        for k in range(frames):
            im.seek(k)
            shots.append(np.asarray(im.convert("L"), dtype=float))
    for px in shots:
        assert px.std() > 5, f"{path} is blank"
    return shots


@pytest.mark.parametrize("example", ["hoecken", "hexapod_tripod"])
def test_report_figures_and_animation_are_drawn(tmp_path, example):
    from pathlib import Path

    from linkage.cli import main

    scene = Path(__file__).parent.parent / "examples" / f"{example}.toml"
    out = tmp_path / "r"
    assert main(["run", str(scene), "--out", str(out), "--samples", "73", "--frames", "6"]) == 0
    check_image(out / "trajectory.png")
    frames = check_image(out / "animation.gif")
    assert len(frames) == 6
    # The mechanism moves: frames differ.
    assert np.abs(frames[0] - frames[3]).max() > 50


def test_drawing_module_needs_no_plotting_library():
    import subprocess
    import sys

    code = "import sys, linkage.drawing; print('matplotlib' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_walker_view_must_be_known():
    w = linkage.catalog.quadruped_hoecken()
    with pytest.raises(linkage.LinkageError, match="view"):
        walker_drawing(w, w.simulate(THETA), "front")
    with pytest.raises(linkage.LinkageError, match="leg_theta"):
        walker_drawing(w, w.simulate(THETA), "side", leg_theta=np.zeros((3, 4)))
    assert math.isfinite(w.simulate(THETA).min_margin)


def _run(example: str, samples: int = 181):
    from pathlib import Path

    from linkage import runner, scene

    sc = scene.load(Path(__file__).parent.parent / "examples" / f"{example}.toml")
    return runner.run(sc, samples=samples)


@pytest.mark.parametrize("example", ["hoecken", "jansen", "peaucellier", "chebyshev"])
def test_trajectory_limits_come_from_the_path_not_the_evolute(example):
    from linkage import report

    res = _run(example)
    assert res.sweep is not None
    d = report._mechanism_drawing(res, res.scene.units)
    fig = report._trajectory(res, d)
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    x, y = (d.positions[..., 0], d.positions[..., 1])
    size = max(np.nanmax(x) - np.nanmin(x), np.nanmax(y) - np.nanmin(y))
    # The view is the linkage and its path with a margin, whatever the evolute does.
    assert max(x1 - x0, y1 - y0) < 1.5 * size
    p = res.sweep.point
    assert np.nanmin(p[:, 0]) >= x0 and np.nanmax(p[:, 1]) <= y1
    unit = res.scene.units or "length units"
    assert ax.get_xlabel() == f"x ({unit})" and ax.get_ylabel() == f"y ({unit})"


def test_hexapod_views_do_not_collapse_to_a_strip():
    from linkage import report

    res = _run("hexapod_tripod")
    views = report._walker_views(res, "m")
    (top, top_equal), (side, side_equal) = views
    assert top.axes == ("x", "y") and top_equal  # the legs' plane, to scale
    assert side.axes == ("x", "z") and not side_equal  # 1.4 mm lift over 0.17 m: not to scale
    fig, axes = report._drawing_figure(views, 5.6)
    for ax in axes:
        h = ax.get_position().height * fig.get_size_inches()[1]
        assert h >= 1.2, "a panel shorter than 1.2 in"
    report._view(axes[1], side, equal=False)
    y0, y1 = axes[1].get_ylim()
    assert y1 - y0 < 0.01  # fitted to the feet's heights and the ground, so the lift shows
    assert "not to scale" in axes[1].get_ylabel() and "(m" in axes[1].get_ylabel()
