"""Rhino (rhino3dm): the .3dm file and the Grasshopper Hops server's geometry.

- :mod:`.file`: NAME.3dm, the folded form and its flat pattern.
- :mod:`.sides`: the folded form as one Brep per side, checked valid.
- :mod:`.faces`: each side's NURBS face, whose natural boundary is the part's edge.
- :mod:`.strings`: the user strings: the design's parameters and the report's numbers.
- :mod:`.hops_geometry`: the objects the Hops server answers with and the sheet it reads.
"""
