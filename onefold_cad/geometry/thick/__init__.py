"""The thick sheet of the exact model (numpy only).

- :mod:`.thick_map`: the map about the exact cone and the smallest relief hole a solid needs.
- :mod:`.slab`: the solid as ruled patches between boundary curves.
- :mod:`.slab_faces`: each side's sheet faces and walls, the B-rep builder's input.
- :mod:`.slab_volume`: the volume integrated from the geometry, a check on the kernel.
"""
