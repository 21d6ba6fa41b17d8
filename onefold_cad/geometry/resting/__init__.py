"""How a folded form rests on the ground: its body, lowest points, toppling
and resting placement (numpy only).

- :mod:`.placement`: stand a form on the ground: its resting placement and stability.
- :mod:`.body`: the body a form is written as: where its lowest point can lie, its mass.
- :mod:`.body_samples`: a body's sample grids, evaluated a family at a time.
- :mod:`.body_families`: a body's pieces evaluated many at once.
- :mod:`.body_pieces`: the pieces beyond the sheet edges' sectors (hole arcs, mitres).
- :mod:`.body_mass`: the centre of mass of a body, integrated.
- :mod:`.body_kinks`: where the thick sheet's sections change form along the arc.
- :mod:`.edge_samples`: where a body samples the sheet's edges, once per sheet.
- :mod:`.pieces`: one-parameter families of points and the search for their lowest.
- :mod:`.zoom`: many minimisations at once, one bracket each.
- :mod:`.lows`: a body's exact lowest points along many directions.
- :mod:`.ground`: how a body meets the ground: the exact plane after toppling.
- :mod:`.topple`: toppling on samples until the centre of mass is supported.
- :mod:`.hull`: convex hulls in the plane.
"""
