"""The shell's local geometry: small functions of a triangle, an edge or a
director, with gradients and Hessians, vectorised over elements (derivations
in docs/mechanics.md, every derivative checked against finite differences in
tests/mechanics/kinematics/).

- :mod:`.triangles`: a face's metric, area and heights, the dihedral angle
  across an edge, the director slopes and their contracted Hessians;
- :mod:`.transport`: an edge's director, parallel-transported along it and
  turned by its angle.
"""
