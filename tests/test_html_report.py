"""The report's ``index.html`` in a real headless Chromium (Debian's ``chromium``), driven over
the DevTools protocol on a pipe (``--remote-debugging-pipe``: no websocket client needed).

Each page must load without a console error or a request to anything but itself, redraw the
mechanism when the slider moves, and show a screenshot that is not blank. Without a browser the
browser tests skip, unless ``CI`` is set: there a missing browser is a failure (``.ci/run``
installs it).
"""

from __future__ import annotations

import base64
import fcntl
import io
import json
import os
import re
import shutil
import subprocess
import tempfile
import time
from collections.abc import Iterator
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from linkage import LinkageError, figures, runner, scene
from linkage.html_report import MAX_FRAMES, frames, page, write_index

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"


def _browser() -> str | None:
    for name in ("chromium", "chromium-browser", "google-chrome", "chrome"):
        found = shutil.which(name)
        if found:
            return found
    return None


def _need_browser() -> str:
    found = _browser()
    if found is None:
        if os.environ.get("CI"):
            pytest.fail("CI is set but no chromium is installed (.ci/run installs Debian's)")
        pytest.skip("chromium is not installed (apt-get install chromium)")
    return found


class Browser:
    """A headless Chromium spoken to over ``--remote-debugging-pipe`` (fd 3 in, fd 4 out,
    NUL-separated JSON messages)."""

    def __init__(self, exe: str, width: int = 1280, height: int = 1000) -> None:
        self.profile = tempfile.mkdtemp(prefix="linkage-chromium-")
        to_child_r, self._to_child = os.pipe()
        self._from_child, from_child_w = os.pipe()
        # The child's fds 3 and 4 must be exactly these pipes.
        args = [
            exe,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            "--hide-scrollbars",
            "--mute-audio",
            f"--window-size={width},{height}",
            f"--user-data-dir={self.profile}",
            "--remote-debugging-pipe",
            "about:blank",
        ]

        # Moved above 9 first so that placing them at 3 and 4 cannot overwrite one another.
        high_r = fcntl.fcntl(to_child_r, fcntl.F_DUPFD, 10)
        high_w = fcntl.fcntl(from_child_w, fcntl.F_DUPFD, 10)

        def fds() -> None:  # in the child, before exec
            os.dup2(high_r, 3)
            os.dup2(high_w, 4)

        self.proc = subprocess.Popen(
            args,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            preexec_fn=fds,
            pass_fds=(3, 4),
        )
        os.close(high_r)
        os.close(high_w)
        os.close(to_child_r)
        os.close(from_child_w)
        self._buf = b""
        self._id = 0
        self.events: list[dict[str, Any]] = []
        self.session = ""

    def close(self) -> None:
        try:
            self.send("Browser.close", browser=True, timeout=5)
        except Exception:
            pass
        try:
            self.proc.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        for fd in (self._to_child, self._from_child):
            try:
                os.close(fd)
            except OSError:
                pass
        shutil.rmtree(self.profile, ignore_errors=True)

    def _read(self, deadline: float) -> dict[str, Any]:
        import select

        while b"\0" not in self._buf:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError("chromium did not answer")
            ready, _, _ = select.select([self._from_child], [], [], left)
            if ready:
                chunk = os.read(self._from_child, 1 << 20)
                if not chunk:
                    raise RuntimeError("chromium closed the pipe")
                self._buf += chunk
        msg, self._buf = self._buf.split(b"\0", 1)
        out: dict[str, Any] = json.loads(msg)
        return out

    def send(
        self, method: str, browser: bool = False, timeout: float = 30, **params: Any
    ) -> dict[str, Any]:
        self._id += 1
        msg: dict[str, Any] = {"id": self._id, "method": method, "params": params}
        if not browser:
            msg["sessionId"] = self.session
        os.write(self._to_child, json.dumps(msg).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._read(deadline)
            if reply.get("id") == self._id:
                if "error" in reply:
                    raise RuntimeError(f"{method}: {reply['error']}")
                result: dict[str, Any] = reply.get("result", {})
                return result
            if "method" in reply:
                self.events.append(reply)

    def wait_event(self, method: str, timeout: float = 30) -> dict[str, Any]:
        deadline = time.monotonic() + timeout
        for k, e in enumerate(self.events):
            if e["method"] == method:
                return self.events.pop(k)
        while True:
            e = self._read(deadline)
            if e.get("method") == method:
                return e
            if "method" in e:
                self.events.append(e)

    def open(self, url: str) -> None:
        if not self.session:
            targets = self.send("Target.getTargets", browser=True)["targetInfos"]
            page_id = next(t["targetId"] for t in targets if t["type"] == "page")
            self.session = self.send(
                "Target.attachToTarget", browser=True, targetId=page_id, flatten=True
            )["sessionId"]
            for domain in ("Page", "Runtime", "Log", "Network"):
                self.send(f"{domain}.enable")
        self.events.clear()
        self.send("Page.navigate", url=url)
        self.wait_event("Page.loadEventFired")

    def js(self, expr: str) -> Any:
        r = self.send("Runtime.evaluate", expression=expr, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError(f"{expr}: {r['exceptionDetails']}")
        return r["result"].get("value")

    def problems(self) -> list[str]:
        """Console errors, uncaught exceptions and warnings logged so far."""
        self.send("Runtime.evaluate", expression="0")  # flush pending events
        out = []
        for e in self.events:
            p = e.get("params", {})
            if e["method"] == "Runtime.exceptionThrown":
                out.append(f"exception: {p['exceptionDetails']}")
            elif e["method"] == "Runtime.consoleAPICalled" and p["type"] in ("error", "warning"):
                out.append(f"console.{p['type']}: {p['args']}")
            elif e["method"] == "Log.entryAdded" and p["entry"]["level"] in ("error", "warning"):
                out.append(f"log: {p['entry']}")
        return out

    def requests(self) -> list[str]:
        return [
            e["params"]["request"]["url"]
            for e in self.events
            if e["method"] == "Network.requestWillBeSent"
        ]

    def screenshot(self) -> bytes:
        data = self.send("Page.captureScreenshot", format="png")["data"]
        return base64.b64decode(data)


@pytest.fixture(scope="module")
def browser() -> Iterator[Browser]:
    b = Browser(_need_browser())
    try:
        yield b
    finally:
        b.close()


def _result(name: str | None) -> figures.Result:
    if name == "slider-crank":
        return _slider_crank()
    sc = scene.parse(scene.DEFAULT_SCENE) if name is None else scene.load(EXAMPLES / name)
    return runner.run(sc)


def _slider_crank() -> figures.Result:
    """An offset slider-crank from the Python API (scenes have no sliders), with a coupler
    point: a run as ``linkage run`` would hand it to the report."""
    from linkage import Mechanism

    m = Mechanism()
    m.fixed("O", (0, 0))
    m.fixed("G", (0, -5))
    m.crank("A", "O", radius=20)
    m.slider("B", "A", 60, "G", direction=(1, 0))
    m.point("P", on=("A", "B"), at=(30, 12))
    t = np.linspace(0, 1, 361)
    theta = 2 * np.pi * t
    sc = scene.parse(
        'name = "slider-crank"\nunits = "mm"\noutputs = ["trajectory"]\n'
        '[mechanism]\ncatalog = "hoecken"\n[drive]\nkind = "constant"\nomega = 6.283185307\n'
    )
    res = figures.Result(scene=sc, time=t, theta=theta, mechanism=m, sweep=m.sweep(theta))
    res.figures.append(figures.Row("stroke", "40", "mm", "exact"))
    return res


def _plot(path: Path, color: tuple[int, int, int]) -> Path:
    from PIL import Image

    Image.new("RGB", (120, 80), color).save(path)
    return path


SCENES = [
    ("hoecken.toml", "mechanism"),
    ("jansen.toml", "mechanism"),
    ("slider-crank", "mechanism"),
    (None, "walker"),
    ("hexapod_tripod.toml", "walker"),
]


def _last_digit(text: str) -> float:
    """Half a unit in the last digit ``text`` shows (and a little more): how far a number
    printed so may be from the value."""
    shown = text.split(".")[1] if "." in text else ""
    return 0.51 * 10.0 ** -len(shown)


def _ink(png: bytes, box: tuple[int, int, int, int] | None = None) -> float:
    """Share of the screenshot's pixels (in ``box``) that differ from its commonest colour."""
    from PIL import Image

    im = Image.open(io.BytesIO(png)).convert("RGB")
    if box is not None:
        im = im.crop(box)
    a = np.asarray(im).reshape(-1, 3).astype(int)
    colours, counts = np.unique(a, axis=0, return_counts=True)
    bg = colours[int(np.argmax(counts))]
    return float(np.mean(np.abs(a - bg).sum(axis=1) > 30))


@pytest.mark.parametrize(("name", "kind"), SCENES, ids=[s[0] or "default" for s in SCENES])
def test_page_in_chromium(browser: Browser, tmp_path: Path, name: str | None, kind: str) -> None:
    res = _result(name)
    plots = [_plot(tmp_path / "a.png", (200, 30, 30)), _plot(tmp_path / "b.png", (30, 30, 200))]
    path = write_index(res, tmp_path, plots)
    assert path == tmp_path / "index.html"
    browser.events.clear()
    browser.open(path.as_uri())
    assert browser.problems() == []
    browser.js("window.linkageReport.setPlaying(false)")
    # Nothing but the page itself is requested (plots are data: URIs, no CDN, no fonts).
    assert [u for u in browser.requests() if not u.startswith("data:")] == [path.as_uri()]

    n = browser.js("window.linkageReport.frames")
    assert n == min(len(res.time), MAX_FRAMES)
    views = browser.js("document.querySelectorAll('#views svg').length")
    assert views == (2 if kind == "walker" else 1)
    # Everything the script drew, as text: moving the slider must change it.
    state = "Array.from(document.querySelectorAll('#views svg *')).map(e => e.outerHTML).join('')"
    readout = "document.getElementById('readout').innerText"

    def move(to: int) -> None:
        browser.js(
            "(() => {const s = document.getElementById('scrub');"
            f"s.value = '{to}'; s.dispatchEvent(new Event('input', {{bubbles: true}}));}})()"
        )

    move(0)
    before, text0 = browser.js(state), browser.js(readout)
    move(n // 3)
    after, text1 = browser.js(state), browser.js(readout)
    assert browser.js("document.querySelector('#views svg').dataset.frame") == str(n // 3)
    assert before != after
    assert text0 != text1
    # The pose really moved: a joint or foot drawn elsewhere (not only a label).
    pos = (
        "Array.from(document.querySelectorAll('#views svg circle'))"
        ".map(c => [+c.getAttribute('cx'), +c.getAttribute('cy')])"
    )
    move(0)
    p0 = np.array(browser.js(pos), dtype=float)
    move(n // 3)
    p1 = np.array(browser.js(pos), dtype=float)
    assert p0.shape == p1.shape and len(p0)
    assert np.nanmax(np.abs(p1 - p0)) > 1.0
    # Drawn where the run put it: the trace point (a mechanism) or the feet in the top view (a
    # walker) move on the page as in the world, at the view's scale, y up.
    k0, k1 = (int(frames(len(res.time))[f]) for f in (0, n // 3))
    if kind == "walker":
        assert res.simulation is not None
        which = "top view"
        world = res.simulation.feet[:, :, :2]
        marks = "circle.foot"
    else:
        assert res.sweep is not None
        which = "mechanism"
        world = res.sweep.point[:, None, :]
        marks = "circle.tracer"
    grab = (
        f"Array.from(document.querySelector('svg[data-view=\"{which}\"]')"
        f".querySelectorAll('{marks}')).map(c => [+c.getAttribute('cx'), +c.getAttribute('cy')])"
    )
    scale = browser.js(f"window.linkageReport.data.views.find(v => v.title === '{which}').unit")
    move(0)
    at0 = np.array(browser.js(grab), dtype=float)
    move(n // 3)
    at1 = np.array(browser.js(grab), dtype=float)
    want = (world[k1] - world[k0]) * scale * np.array([1.0, -1.0])
    assert at1 - at0 == pytest.approx(want, abs=1.5)
    # The read-out shows the sample the slider is on, with the scene's units.
    rows = browser.js(
        "Array.from(document.querySelectorAll('#readout tr'))"
        ".map(r => Array.from(r.children).map(c => c.textContent))"
    )
    table = {label: (value, unit) for label, value, unit in rows}
    k = int(frames(len(res.time))[n // 3])
    assert float(table["time"][0]) == pytest.approx(res.time[k], abs=_last_digit(table["time"][0]))
    assert table["time"][1] == "s"
    assert table["crank angle"][1] == "°"
    length = figures.length_unit(res.scene)
    if kind == "walker":
        assert table["stability margin"][1] == length
        assert res.simulation is not None
        assert table["feet down"][0].startswith(str(int(res.simulation.stance[k].sum())))
    else:
        assert res.sweep is not None
        x = table[f"trace {res.sweep.trace} x"]
        assert x[1] == length
        assert float(x[0]) == pytest.approx(res.sweep.point[k, 0], abs=_last_digit(x[0]))
    # The figures table and both plots.
    rows = browser.js("document.querySelectorAll('table.figures tbody tr').length")
    assert rows == len(res.figures)
    imgs = browser.js(
        "Array.from(document.querySelectorAll('.plots img')).map(i => i.naturalWidth)"
    )
    assert imgs == [120, 120]
    # Playing advances the frame.
    browser.js("window.linkageReport.show(0); window.linkageReport.setPlaying(true)")
    browser.js("new Promise(r => setTimeout(r, 400))")
    assert browser.js("window.linkageReport.frame()") > 0
    browser.js("window.linkageReport.setPlaying(false)")
    # A screenshot of the animation is not blank.
    move(n // 3)
    png = browser.screenshot()
    rect = browser.js(
        "(() => {const r = document.getElementById('views').getBoundingClientRect();"
        "return [r.left, r.top, r.right, r.bottom].map(Math.round);})()"
    )
    assert _ink(png, tuple(rect)) > 0.01
    shots = os.environ.get("LINKAGE_SCREENSHOTS")
    if shots:
        Path(shots).mkdir(parents=True, exist_ok=True)
        full = browser.send("Page.captureScreenshot", format="png", captureBeyondViewport=True)
        Path(shots, f"{res.scene.name}.png").write_bytes(base64.b64decode(full["data"]))
    assert browser.problems() == []


def test_synthesis_page_in_chromium(browser: Browser, tmp_path: Path) -> None:
    """A [synthesis] scene's page: no motion and no script, the figures table, the candidates
    and the plot; no console error, nothing requested but the page."""
    res = runner.run(scene.load(EXAMPLES / "synthesis_foot.toml"))
    assert res.synthesis is not None
    path = write_index(res, tmp_path, [_plot(tmp_path / "synthesis.png", (30, 120, 200))])
    browser.events.clear()
    browser.open(path.as_uri())
    assert browser.problems() == []
    assert [u for u in browser.requests() if not u.startswith("data:")] == [path.as_uri()]
    assert browser.js("document.querySelectorAll('script, #views, #scrub').length") == 0
    figures_rows = "document.querySelectorAll('table.figures:not(#candidates) tbody tr').length"
    assert browser.js(figures_rows) == len(res.figures)
    cells = browser.js(
        "Array.from(document.querySelectorAll('#candidates tbody tr'))"
        ".map(r => Array.from(r.children).map(c => c.textContent))"
    )
    assert len(cells) == len(res.synthesis.candidates)
    assert [row[0] for row in cells] == [str(k + 1) for k in range(len(cells))]
    assert cells[0][-1] in ("open", "crossed") and cells[0][4] == "crank-rocker"
    # A closed target's candidates say how far their curve strays from the target's polygon
    # (here the polygon's chords: the fit is exact at the points).
    heads = browser.js(
        "Array.from(document.querySelectorAll('#candidates thead th')).map(c => c.textContent)"
    )
    assert heads[3] == "curve → polygon (mm)", heads
    c0 = res.synthesis.candidates[0]
    assert float(cells[0][3]) == pytest.approx(c0.back, rel=5e-3) and c0.back > 10 * c0.error
    # The candidates table fits the page at 1280 px: it had scrolled sideways at 1400.
    wide = "(() => {const w = document.querySelector('.wide'); return [w.scrollWidth, w.clientWidth];})()"
    scroll, client = browser.js(wide)
    assert scroll <= client, (scroll, client)
    imgs = browser.js(
        "Array.from(document.querySelectorAll('.plots img')).map(i => i.naturalWidth)"
    )
    assert imgs == [120]
    assert _ink(browser.screenshot()) > 0.01
    shots = os.environ.get("LINKAGE_SCREENSHOTS")
    if shots:
        Path(shots).mkdir(parents=True, exist_ok=True)
        full = browser.send("Page.captureScreenshot", format="png", captureBeyondViewport=True)
        Path(shots, f"{res.scene.name}.png").write_bytes(base64.b64decode(full["data"]))


def test_missing_browser_skips_only_outside_ci(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setattr(shutil, "which", lambda _name: None)
    monkeypatch.delenv("CI", raising=False)
    with pytest.raises(pytest.skip.Exception):
        _need_browser()
    monkeypatch.setenv("CI", "true")
    with pytest.raises(pytest.fail.Exception):
        _need_browser()


def test_page_is_self_contained_and_small(tmp_path: Path) -> None:
    res = _result("jansen.toml")
    text = page(res, [_plot(tmp_path / "a.png", (1, 2, 3))])
    # No reference to anything outside the file.
    refs = re.findall(r"""(?:src|href|url)\s*[=(]\s*["']?([^"')\s>]*)""", text)
    assert refs and all(r.startswith("data:") for r in refs), refs
    assert "http://" not in text.replace("http://www.w3.org/2000/svg", "")
    assert "https://" not in text
    assert len(text.encode()) < 400_000


def test_frames_subsampled() -> None:
    assert list(frames(5)) == [0, 1, 2, 3, 4]
    idx = frames(100_001)
    assert len(idx) == MAX_FRAMES
    assert idx[0] == 0 and idx[-1] == 100_000
    assert np.all(np.diff(idx) > 0)


def test_long_run_embeds_at_most_max_frames(tmp_path: Path) -> None:
    res = runner.run(scene.load(EXAMPLES / "hoecken.toml"), samples=5001)
    text = page(res, [])
    data = json.loads(re.search(r"id=linkage-data>(.*?)</script>", text, re.S).group(1))  # type: ignore[union-attr]
    assert len(data["views"][0]["points"]) == MAX_FRAMES
    assert all(len(c["values"]) == MAX_FRAMES for c in data["readout"])


def test_figures_and_text_are_escaped(tmp_path: Path) -> None:
    res = _result("hoecken.toml")
    res.figures.append(("<b>bold</b> & co", "1 < 2", "mm", "</script>"))
    text = page(res, [])
    assert "<b>bold</b>" not in text
    assert "&lt;b&gt;bold&lt;/b&gt; &amp; co" in text
    assert text.count("</script>") == 2


@pytest.mark.parametrize("name", ["jansen.toml", None], ids=["jansen", "default"])
def test_drawings_given_are_used_as_built(name: str | None) -> None:
    from linkage.drawing import mechanism_drawing, walker_drawing
    from linkage.html_report import _views

    res = _result(name)
    u = res.scene.units
    if res.walker is not None:
        assert res.simulation is not None
        given = [walker_drawing(res.walker, res.simulation, v, units=u) for v in ("top", "side")]
    else:
        assert res.mechanism is not None and res.sweep is not None
        given = [mechanism_drawing(res.mechanism, res.sweep, u)]
    assert _views(res, given) == _views(res)
    short = replace(given[0], positions=given[0].positions[:3])
    with pytest.raises(LinkageError, match="3 samples"):
        _views(res, [short])


PARTIAL = """
name = "partial"
units = "mm"
outputs = ["trajectory", "velocity"]
[mechanism]
ground = 30
crank = 20
coupler = 12
rocker = 25
[drive]
kind = "constant"
omega = 1.0
samples = 361
"""


def test_samples_that_do_not_assemble_are_gaps(tmp_path: Path) -> None:
    res = runner.run(scene.parse(PARTIAL))
    assert res.sweep is not None
    valid = res.sweep.valid
    assert 0 < valid.sum() < len(valid)
    text = page(res, [])
    found = re.search(r"id=linkage-data>(.*?)</script>", text, re.S)
    assert found is not None
    data = json.loads(found.group(1))
    rows = data["views"][0]["points"]
    assert [r is None for r in rows] == list(~valid)
    x = next(c for c in data["readout"] if c["label"].endswith(" x"))
    assert [v is None for v in x["values"]] == list(~valid)


def test_the_read_out_names_the_crank_angle_of_a_phased_crank(tmp_path) -> None:  # type: ignore[no-untyped-def]
    # An exported synthesis candidate's crank has a phase: the page had shown the drive angle
    # as "crank angle" (41.5° where the crank was at 221.5°).
    from linkage import html_report, runner, scene

    text = (ROOT / "examples" / "hoecken_by_joints.toml").read_text()
    for phase, labels in ((0.0, ["crank angle"]), (90.0, ["drive angle θ", "crank angle"])):
        path = tmp_path / "leg.toml"
        path.write_text(text.replace("radius = 10.0 }", f"radius = 10.0, phase_deg = {phase} }}"))
        res = runner.run(scene.load(path))
        idx = np.arange(0, len(res.time), 37)
        cols = {c["label"]: c["values"] for c in html_report._readout(res, idx)}
        assert [k for k in cols if "angle" in k] == labels
        want = np.mod(np.degrees(res.theta[idx]) + phase, 360.0)
        assert cols["crank angle"] == pytest.approx(want, abs=0.05)
