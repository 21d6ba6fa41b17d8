"""The files of ``onefold simulate``: a simulation's form, fields and pictures.

- :mod:`.glb`: the standing (or released) sheet as binary glTF 2.0.
- :mod:`.vtu`: the results for ParaView and other VTK readers (meshio).
- :mod:`.inp`: the structural check as a CalculiX / Abaqus input file.
- :mod:`.inp_mesh`: its mesh: each facet curved onto the surface and split in four.
- :mod:`.pictures`: NAME-deviation.png and NAME-stress.png.
- :mod:`.colour_scale`: the one colour scale of the deviation, shared by every view.
- :mod:`.stress_scale`: the stress picture's colour scale, yield marked.
"""
