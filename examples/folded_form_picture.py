"""The folded form as a picture, for a notebook or a report.

    python examples/folded_form_picture.py [OUTDIR]

In Jupyter, the last lines show the pictures inline (IPython's display);
run as a script, they print the files' paths.
"""

import sys
from pathlib import Path

import onefold_cad as of

out = Path(sys.argv[1] if len(sys.argv) > 1 else "out")
out.mkdir(parents=True, exist_ok=True)

design = of.load_template("table1-row1")
form = of.export(design, out / "form.png")  # the form as it stands, with a legend
flat = of.export(design, out / "flat.svg")  # the flat pattern at true size
model = of.export(design, out / "form.glb")  # for a 3D viewer (metres, y up)

try:  # in a notebook
    from IPython import get_ipython
    from IPython.display import SVG, Image, display

    if get_ipython() is None:
        raise ImportError
    display(Image(filename=str(form)), SVG(filename=str(flat)))
except ImportError:  # as a script
    print(form, flat, model, sep="\n")
