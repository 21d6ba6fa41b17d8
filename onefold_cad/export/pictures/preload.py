"""Imported ahead of a sweep's workers: what a thumbnail draws with.

A sweep's process pool forks its workers from a forkserver that has
imported the evaluation code (:mod:`onefold_cad.sweep.backends`); with
thumbnails asked for it imports this module too, so the workers start with
matplotlib's Agg canvas, its 3D axes and the preview's own modules loaded
(about 1.5 s of CPU each worker no longer spends on its first design).
Nothing else imports it: the rest of the package loads matplotlib only
when it draws.
"""

from __future__ import annotations

import matplotlib.backends.backend_agg  # noqa: F401
import matplotlib.figure  # noqa: F401
import mpl_toolkits.mplot3d  # noqa: F401

import onefold_cad.export.pictures.preview  # noqa: F401
import onefold_cad.export.pictures.reuse  # noqa: F401
import onefold_cad.export.pictures.surface_image  # noqa: F401
