"""``onefold explore``: the paper's interactive design tool, in the browser.

A local server (:mod:`onefold_cad.explore.server`, 127.0.0.1 only) serves one
page (its files and policy: :mod:`~onefold_cad.explore.page`): sliders for
the frame curve, the apex position, the sheet and the material; the folded
form in 3D (three.js, vendored: works offline); the flat pattern; the numbers
and every message; and downloads of the current design.
The Python solver is the one source of truth: each control change asks the
server for the new state (:func:`onefold_cad.explore.state.design_state`),
and the page only draws what it gets. Its Simulate button and Steel view
show the design as steel (:mod:`~onefold_cad.explore.simulation`,
:mod:`~onefold_cad.explore.steel`); its Compensate action runs ``onefold
compensate`` as a coarse preview in the background
(:mod:`~onefold_cad.explore.compensation`).
"""

from onefold_cad.explore.server import DEFAULT_PORT, ExploreServer, make_server, serve

__all__ = ["DEFAULT_PORT", "ExploreServer", "make_server", "serve"]
