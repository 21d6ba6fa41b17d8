"""A design from values to a STEP for CAD and a DXF for the workshop.

    python examples/design_to_step_dxf.py [OUTDIR]

A 1200 x 2400 mm sheet folded along its diagonal, the apex 40 % along it,
1.5 mm steel: the same design, and the same files, as
``onefold build --rectangle 1200x2400 --apex-fraction 0.4 --alpha 35 --beta 30
--thickness 1.5 --name my-fold --body shell --formats step,dxf``.
"""

import sys
from pathlib import Path

import onefold_cad as of

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

design = of.make_design(
    rectangle=(1200, 2400), apex_fraction=0.4, alpha=35, beta=30, thickness=1.5, name="my-fold"
)
# the folded reference surface as it stands (body="solid", the default for a sheet
# with thickness, writes the sheet's solid: a CAD kernel's work of some seconds)
step = of.export(design, out / f"{design.name}.step", body="shell")
dxf = of.export(design, out / f"{design.name}.dxf")  # the flat pattern, bends annotated
print(step, dxf, sep="\n")
