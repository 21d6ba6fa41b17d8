"""Pictures drawn with matplotlib: the folded form and a sweep.

- :mod:`.preview`: NAME.png, a shaded 3D preview of the form on the ground.
- :mod:`.figure3d`: what the 3D pictures share: light, camera, shading, axes.
- :mod:`.surface_image`: the preview's shaded surface as one artist
  (projected and depth-ordered as matplotlib's collection does, painted by
  Agg in one call).
- :mod:`.reuse`: one emptied 3D figure per size and thread (the thumbnails).
- :mod:`.preload`: what a thumbnail draws with, imported by a sweep's forkserver.
- :mod:`.sweep_plot`: a sweep's parallel coordinates, the Pareto front marked.
"""
