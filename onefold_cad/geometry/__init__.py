"""The pure geometry core (numpy and scipy only; never build123d or ezdxf):
the paper's construction from the frame curve to the folded sheet, and how
the folded form rests on the ground.

The construction (paper sections 3.2 to 3.4):

- :mod:`.frame_curve`: the frame curve's frozen inputs and the scalars of its arc.
- :mod:`.arc`: points of the frame curve and the exact cone's frames along it.
- :mod:`.surface`: the direction-surface interface of the fan and the cone.
- :mod:`.fan`: the paper's direction-surface, a fan of planar triangles.
- :mod:`.fan_folds`: the paper model's signed fold angle along each ruling.
- :mod:`.root`: the root search of the angle condition past its maximum.
- :mod:`.solver`: the apex, the non-trivial root of the angle condition.
- :mod:`.sheet`: the flat sheet, a simple polygon star-shaped about H.
- :mod:`.folding`: the flat sheet folded onto the solved direction-surface.
- :mod:`.developability`: the folded form measured against the flat sheet.
- :mod:`.material`: the sheet's material and fabrication inputs, its faces.
- :mod:`.bend_model`: the bend model (setback, allowance, deduction).

Helpers shared by all:

- :mod:`.checks`: the value checks of the frozen parameters, the bounds of magnitudes.
- :mod:`.numeric`: small numeric helpers, one home per formula.
- :mod:`.polygon`: simple plane polygons and the largest circle inside one.
- :mod:`.nearby`: which points lie within a tolerance of a set of targets.

The families, one folder each (its ``__init__`` maps it):

- :mod:`.cone`: the exact model's direction-surface, the cone over the arc.
- :mod:`.thick`: the thick sheet: its map, solid patches, faces and volume.
- :mod:`.resting`: a body's lowest points, the ground, toppling, the resting placement.
"""
