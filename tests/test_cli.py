"""The ``linkage`` command: the main job prints real figures; errors exit non-zero."""

from __future__ import annotations

import re
import subprocess
import sys

import numpy as np

from linkage.cli import hoecken_report, main


def test_run_prints_hoecken_table(capsys):
    assert main(["run", "--samples", "721"]) == 0
    out = capsys.readouterr().out
    assert "crank-rocker" in out and "64.286" in out
    # The stance straight part: within 0.1 mm of y = 40, so it must at least span the exact
    # straight points x = 0 … 40 (hand-computed in the core's golden test).
    m = re.search(r"stance \(within 0.1 mm of lowest\) length\s+([0-9.]+)", out)
    assert m and 40.0 < float(m.group(1)) < 48.0


def test_report_figures_are_consistent():
    rows = {r[0]: r for r in hoecken_report(1441)}
    lo, hi = (float(x) for x in rows["foot path y range"][1].split(" … "))
    # Printed to 3 decimals: agree to half a unit of the last digit.
    assert abs(lo - 40.0) <= 5e-4 and abs(hi - 2 * np.sqrt(600)) <= 5e-4
    lift = float(rows["lift height (swing above stance)"][1])
    assert abs(lift - (hi - lo)) < 2e-3


def test_console_script_and_module_agree():
    out = subprocess.run(
        [sys.executable, "-m", "linkage", "catalog"], capture_output=True, text=True, check=True
    ).stdout
    for name in ("hoecken", "evans_a", "peaucellier", "hart", "hoecken_pantograph"):
        assert name in out


def test_run_with_scene_is_a_clear_error(capsys):
    assert main(["run", "scene.toml"]) == 2
    assert "scene files are not supported yet" in capsys.readouterr().err
