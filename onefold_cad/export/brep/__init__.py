"""The folded form as a B-rep (build123d, OCP) and its STEP file.

- :mod:`.part`: the design's part: exact faces, one shell, a solid.
- :mod:`.cone_faces`: the exact model's faces, patches of the cone trimmed by the sheet's edge.
- :mod:`.cone_patch`: the exact cone held as an OCC rational B-spline surface.
- :mod:`.fan_faces`: the paper model's faces, its planar triangles.
- :mod:`.solid`: the sheet as a solid of thickness t, built face by face.
- :mod:`.bspline_fit`: B-spline curves fitted through points to a tolerance.
- :mod:`.measure`: area and volume of B-rep shapes.
- :mod:`.part_numbers`: the report's ``step`` section from the part a writer built.
- :mod:`.kernel_budget`: the CAD kernel's time budget for one part.
- :mod:`.step_checks`: the part's pre-flight checks, numpy only, before any kernel call.
- :mod:`.step`: NAME.step, deterministic bytes, read back before it is moved into place.
"""
