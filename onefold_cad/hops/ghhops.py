"""ghhops-server, imported with its logging kept to itself.

``ghhops_server.logger`` calls ``logging.basicConfig(level=DEBUG)`` when it
is imported: every library's debug messages in the process would then go to
stderr. This module imports it and moves the handler that call added from
the root logger to ghhops' own ``Hops`` logger (its request lines, at INFO),
giving the root logger its level back. The Hops server imports ghhops-server
from here only.
"""

from __future__ import annotations

import logging

_ROOT = logging.getLogger()
_HANDLERS, _LEVEL = list(_ROOT.handlers), _ROOT.level

import ghhops_server  # noqa: E402  (after the root logger's state is noted)
from ghhops_server.component import HopsComponent  # noqa: E402
from ghhops_server.logger import hlogger  # noqa: E402
from ghhops_server.middlewares import HopsDefault, hopsdefault  # noqa: E402

__all__ = ["HopsComponent", "HopsDefault", "ghhops_server", "hlogger", "hopsdefault"]


def _contain() -> None:
    added = [h for h in _ROOT.handlers if h not in _HANDLERS]
    for h in added:
        _ROOT.removeHandler(h)
        hlogger.addHandler(h)
    if added:
        hlogger.propagate = False
    _ROOT.setLevel(_LEVEL)


_contain()
