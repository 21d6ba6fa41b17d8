"""Fabrication: the part's rules that ``solve`` and every writer share (relief
hole, bend limits, mass, default body, resting placement), the flat pattern,
the bend table and the report. Numpy only: no CAD or plotting library.
"""
