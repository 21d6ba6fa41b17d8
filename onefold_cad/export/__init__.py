"""The adapters that write files: one per format, reading a built design
(``Design``, its fold, the flat pattern and report of ``fabrication``) and
never re-deriving geometry. build123d, OCP, ezdxf, matplotlib, rhino3dm,
ifcopenshell, trimesh and meshio are imported only here, each inside the
adapter that needs it.

The registry, the staging and the one-module formats:

- :mod:`.writers`: the files ``onefold build`` can write, one ``Writer`` each.
- :mod:`.write_checks`: what the writers would refuse, raised before any file exists.
- :mod:`.build_context`: one design being built: its fold, options and shared parts.
- :mod:`.atomic`: all-or-nothing file output (a staging folder, then one commit).
- :mod:`.commit_steps`: the steps of a commit of staged files.
- :mod:`.files`: a design's files staged and committed (``onefold build``'s
  and the scripting API's ``write_files``, one path).
- :mod:`.report_file`: NAME.json, the report written atomically.
- :mod:`.bend_csv`: NAME-bends.csv, the bend table's rows.
- :mod:`.cone_csv`: NAME-cones.csv, the cones' radii per ruling station.
- :mod:`.glb`: NAME.glb, the folded form as binary glTF 2.0.
- :mod:`.aligned_plane`: a planar face's plane with its axes along the face
  (so OCCT's default integration measures it).
- ``onefold compensate``'s files: :mod:`.compensation_picture` (design,
  uncompensated and compensated steel side by side), :mod:`.standing_form`
  (a simulated standing form as GLB and STEP), :mod:`.springback_notes` (the
  angles to fold to and after springback in the DXF notes and bend sheet).

The families, one folder each (its ``__init__`` maps it):

- :mod:`.brep`: the folded form as a B-rep (faces, shell, solid) and NAME.step.
- :mod:`.dxf`: the flat pattern's drawings: NAME.dxf, the cut DXF, notes, previews.
- :mod:`.fold`: NAME.fold for origami tools: the file, its fan and its mesh.
- :mod:`.rhino`: NAME.3dm and the Grasshopper Hops server's geometry (rhino3dm).
- :mod:`.site`: the files of ``onefold site`` for a site as a whole.
- :mod:`.simulation`: the files of ``onefold simulate``: form, fields, pictures.
- :mod:`.pictures`: the 3D preview and a sweep's picture (matplotlib).
- :mod:`.loads`: the files of ``onefold loads``: the cases' CSV and picture.
"""
