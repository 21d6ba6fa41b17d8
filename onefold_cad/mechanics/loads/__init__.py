"""Outdoor loads on the standing sheet and what holds it to the ground.

- ``surface``: the faces' areas and outward normals, a face pressure or a
  load on the projected area lumped to the nodes;
- ``wind``: EN 1991-1-4's peak velocity pressure (terrain categories) and the
  canopy's overall coefficients, the wind's nodal loads for a direction;
- ``snow``: EN 1991-1-3's roof snow load ``s = mu_1 C_e C_t s_k``;
- ``point``: a point load (a person) at a point of the flat sheet;
- ``combinations``: EN 1990's combinations (EQU, STR, SLS) as named cases;
- ``response``: the linear response of a shell state to load vectors
  (tangent stiffness, supports, reactions);
- ``plastic_limit``: a load ratio ramped on a shell of J2 sections (ideal
  elastic-plastic): the plastic limit ``r_R`` (EN 1993-1-6 GMNA);
- ``strength``: the STR cases' verdicts from their J2 load paths;
- ``feet``: the contacts grouped into feet, and the rigid-body checks
  (sliding, a foot lifting, tipping) and the ballast a foot needs;
- ``spec``: the load and support parameters, checked;
- ``outdoors``: the pipeline on a design, and ``results`` what it found.
"""
