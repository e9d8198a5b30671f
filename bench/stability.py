"""The full stiff/extreme-case report: every family of tests/stability_cases.py over its whole
range, as a table (bench/results/stability.md). The CI runs a subset (tests/test_stability.py).

    python bench/stability.py
"""

from __future__ import annotations

import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "tests"))
import stability_cases as sc  # noqa: E402


def main() -> int:
    families = {
        "dyad near toggle, stretched": sc.toggle_dyad([1e-4, 1e-6, 1e-8, 1e-10, 1e-12]),
        "dyad near toggle, folded": sc.toggle_dyad(
            [1e-4, 1e-6, 1e-8, 1e-10, 1e-12], stretched=False
        ),
        "link-length ratios": sc.link_ratios([1e-6, 1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6], samples=72),
        "pivots far from the origin": sc.far_pivots([1e2, 1e4, 1e6, 1e8], samples=72),
        "change points through flat positions": sc.singular_passes((0.25, 1.0, 10.0, 45.0, 90.0)),
        "rates near a toggle": sc.rates_near_toggle([1e-2, 1e-4, 1e-6, 1e-8, 1e-10, 1e-12]),
    }
    lines = [
        "| family | case | max error | error / bound | branch flips | note |",
        "|---|---|---:|---:|---:|---|",
    ]
    worst = 0.0
    for fam, rows in families.items():
        for case, err, ratio, flips, note in rows:
            lines.append(f"| {fam} | {case} | {err:.1e} | {ratio:.2f} | {flips} | {note} |")
            worst = max(worst, ratio)
    text = "\n".join(lines)
    print(text)
    out = ROOT / "bench" / "results"
    out.mkdir(parents=True, exist_ok=True)
    (out / "stability.md").write_text(text + "\n")
    print(f"largest error / bound: {worst:.2f}; wrote {out}/stability.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
