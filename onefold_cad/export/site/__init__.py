"""The files of ``onefold site`` for a site as a whole (each sheet's own
files are ``onefold build``'s).

- :mod:`.writers`: one writer per file, the registry behind ``--formats``.
- :mod:`.context`: one site being built: its sheets as they stand.
- :mod:`.mesh`: a placed part's triangle mesh (OCCT's mesher).
- :mod:`.clearance`: the clearance check on the sheets' exact B-reps.
- :mod:`.plan`: SITE-plan.dxf, the site plan seen from above.
- :mod:`.picture`: SITE.png, every sheet as it stands.
- :mod:`.order`: SITE-order.csv, the bill of materials.
- :mod:`.ifc`: SITE.ifc, the site for BIM (IFC4, IfcOpenShell).
"""
