"""A parameter study without the command line: how the fold angle and the
resting height follow the arc's opening alpha.

    python examples/parameter_study.py [OUTDIR]

Writes OUTDIR/alpha-study.csv, one row per alpha (the report's numbers).
"""

import csv
import sys
from pathlib import Path

import onefold_cad as of

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

rows = []
for alpha in (20.0, 35.0, 50.0, 65.0):
    design = of.make_design("paper-square", alpha=alpha)  # named paper-square-alpha20 ...
    report = of.design_report(design)
    rows.append(
        {
            "alpha_deg": alpha,
            "apex_height": report["direction_surface"]["apex_height"],
            "fold_angle_deg": report["fold_angles_deg"]["plus_x"],
            "resting_height": report["resting"]["height"],
        }
    )

table = out / "alpha-study.csv"
with table.open("w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
for r in rows:
    print(", ".join(f"{k} {v:.4g}" for k, v in r.items()))
print(table)
