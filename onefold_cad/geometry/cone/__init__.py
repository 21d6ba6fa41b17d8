"""The exact model's direction-surface: the cone from the apex over the arc.

- :mod:`.cone`: the cone (:class:`~onefold_cad.geometry.cone.cone.ExactCone`).
- :mod:`.rule`: its quadrature, Gauss-Legendre panels graded towards the singularities.
- :mod:`.nodes`: its developed angle from the node table, for many points.
"""
