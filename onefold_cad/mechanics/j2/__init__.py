"""J2 (von Mises) plasticity through the sheet's thickness, from the material
point to ``onefold simulate --law j2``'s stages.

- :mod:`.law`: plane-stress J2 with linear isotropic and kinematic hardening:
  the return mapping, its consistent tangent and incremental energy;
- :mod:`.section`: a section's points through the thickness (composite
  Simpson), its resultants and their tangent;
- :mod:`.layered`: every face of the shell a section, its internal variables;
- :mod:`.stages`: forming, release and standing with the sections;
- :mod:`.measures`: what the stages say (surface stresses, plastic strains,
  the work of forming, resultants);
- :mod:`.simulate`: ``simulate``'s stages with the J2 law.
"""
