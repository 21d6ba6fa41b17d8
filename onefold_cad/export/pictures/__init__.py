"""Pictures drawn with matplotlib: the folded form and a sweep.

- :mod:`.preview`: NAME.png, a shaded 3D preview of the form on the ground.
- :mod:`.figure3d`: what the 3D pictures share: light, camera, shading, axes.
- :mod:`.sweep_plot`: a sweep's parallel coordinates, the Pareto front marked.
"""
