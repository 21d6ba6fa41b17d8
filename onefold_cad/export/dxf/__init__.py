"""The flat pattern's drawings (ezdxf) for the laser and the shop.

- :mod:`.pattern`: NAME.dxf, the flat pattern with its bend lines and notes.
- :mod:`.cut`: NAME-cut.dxf, the blank for the laser alone.
- :mod:`.notes`: the text of the DXF's NOTES layer.
- :mod:`.preview`: the PNG and SVG previews of the DXF (ezdxf's drawing add-on).
"""
