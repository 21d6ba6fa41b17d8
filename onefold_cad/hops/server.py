"""The Hops server: ghhops-server's components, metadata and standard-library
HTTP server, with onefold's answers and errors.

ghhops-server (McNeel's ``ghhops_server``) gives the routes (``GET /`` lists
the components, ``GET /onefold/solve`` describes one, ``POST /solve`` with
the component in ``pointer`` solves, as Hops sends it; ``POST
/onefold/solve`` too), the parameters' metadata and how outputs are encoded
(rhino3dm's ``Encode`` for geometry). :class:`OneFoldHops` reads a request's
inputs itself (:func:`~onefold_cad.hops.inputs.read_values`: ghhops-server
1.5.5 cannot read an input without data, which Hops sends for an empty
optional input) and answers as compute does (Resthopper's ``Schema``):
``{"values": [...], "warnings": [...], "errors": []}`` with status 200, or
``{"values": [], "errors": [MESSAGE]}`` with status 500, which Hops shows as
the component's error. MESSAGE is the command's one-line message for the
same value (``--alpha: must be in (0, 90) deg, got 95``), never a traceback:
an unexpected failure is one line too, its traceback on the server's stderr.
A request the machine has not the memory for (``MemoryError``) is answered
the same way (``out of memory (...)``, one line in the log) and the server
goes on.

A request's ``template`` is a name (:func:`~onefold_cad.hops.guard.resolve_template`:
the shipped templates and those of the server's folder, never a path), and
the HTTP is :mod:`onefold_cad.hops.http`'s (Host and Origin checked, bodies
and connections bounded, every malformed request answered in one line).
"""

from __future__ import annotations

import json
import sys
import traceback
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from onefold_cad.errors import OneFoldError, memory_message
from onefold_cad.flags.parser import UsageError
from onefold_cad.hops.components import (
    FIT_OUTPUTS,
    SOLVE_OUTPUTS,
    Answer,
    HopsOutput,
    fit_answer,
    solve_answer,
)
from onefold_cad.hops.ghhops import HopsComponent, HopsDefault
from onefold_cad.hops.ghhops import ghhops_server as hs
from onefold_cad.hops.guard import allowed_hosts, resolve_template
from onefold_cad.hops.http import (
    HopsHandler,
    HopsServer,
    RequestError,
    error_answer,
    parse_request,
)
from onefold_cad.hops.inputs import (
    FIT_INPUTS,
    SOLVE_INPUTS,
    HopsInput,
    StaleInputsError,
    read_values,
)

__all__ = ["CATEGORY", "COMPONENTS", "Component", "OneFoldHops", "error_answer", "make_server"]

#: The Grasshopper tab the components are listed under.
CATEGORY = "OneFold"


@dataclass(frozen=True)
class Component:
    """A Hops component of the server.

    Attributes:
        uri: its path (``/onefold/solve``): the Hops component's Path is the
            server's address followed by it.
        name, nickname, description: what Grasshopper shows.
        inputs, outputs: its parameters, in order.
        answer: ``(values, request) -> Answer``: the values read from the
            request, and the request's JSON (for ``modelunits``).
    """

    uri: str
    name: str
    nickname: str
    description: str
    inputs: tuple[HopsInput, ...]
    outputs: tuple[HopsOutput, ...]
    answer: Callable[[Mapping[str, Any], Mapping[str, Any]], Answer]


#: The components the server offers.
COMPONENTS: tuple[Component, ...] = (
    Component(
        "/onefold/solve",
        "onefold solve",
        "OneFold",
        "Solve a One-Fold design as `onefold solve` does: the folded form, its creases "
        "and apex, the flat pattern and the report's numbers",
        SOLVE_INPUTS,
        SOLVE_OUTPUTS,
        lambda values, request: solve_answer(values, request.get("modelunits")),
    ),
    Component(
        "/onefold/fit",
        "onefold fit",
        "OneFoldFit",
        "Find alpha, beta and h_c whose resting form has a target height and span, as "
        "`onefold fit` does (the template's sheet and material)",
        FIT_INPUTS,
        FIT_OUTPUTS,
        lambda values, request: fit_answer(values),
    ),
)

_PARAMS = {
    "number": hs.HopsNumber,
    "integer": hs.HopsInteger,
    "text": hs.HopsString,
    "curve": hs.HopsCurve,
    "brep": hs.HopsBrep,
    "line": hs.HopsLine,
    "point": hs.HopsPoint,
}


def _param(name: str, kind: str, description: str, many: bool, optional: bool) -> Any:
    """A ghhops parameter; an optional input's metadata says ``AtLeast`` 0
    (ghhops 1.5.5 writes 1 whatever ``optional`` says, and Hops makes an input
    optional only for 0)."""
    base = _PARAMS[kind]

    class Param(base):  # type: ignore[misc,valid-type]
        def encode(self) -> dict[str, Any]:
            data: dict[str, Any] = super().encode()
            if self.optional:
                data["AtLeast"] = 0
            return data

    access = hs.HopsParamAccess.LIST if many else hs.HopsParamAccess.ITEM
    return Param(name, name, description, access=access, optional=optional)


class OneFoldHops(HopsDefault):
    """ghhops-server's standard-library server with :data:`COMPONENTS`."""

    def __init__(
        self, components: Sequence[Component] = COMPONENTS, template_dir: Path | None = None
    ) -> None:
        hs.Hops()  # sets ghhops' rhino3dm codec (the params module's encoder)
        super().__init__()
        self.template_dir = template_dir
        self.specs: dict[str, Component] = {}
        for c in components:
            self.specs[c.uri] = c
            self._components[c.uri] = HopsComponent(
                uri=c.uri,
                name=c.name,
                nickname=c.nickname,
                desc=c.description,
                cat=CATEGORY,
                subcat="Design",
                icon=None,
                inputs=[_param(i.name, i.kind, i.description, False, not i.required)
                        for i in c.inputs],
                outputs=[_param(o.name, o.kind, o.description, o.many, False)
                         for o in c.outputs],
                handler=c.answer,
            )  # fmt: skip

    def solve(self, uri: str, payload: Any) -> tuple[bool, str]:
        """ghhops' entry: ``payload`` (the body, bytes or text) read and solved
        as :meth:`solve_request` does; a body that is not Hops' JSON, or a
        component that does not exist, is an error answer."""
        try:
            raw = payload if isinstance(payload, bytes) else str(payload).encode("utf-8")
            return self.solve_request(uri, parse_request(raw))
        except RequestError as exc:
            return False, error_answer(f"the request is not Hops' JSON: {exc}")
        except LookupError as exc:
            return False, error_answer(str(exc.args[0]) if exc.args else "no such component")

    def solve_request(self, uri: str, request: Mapping[str, Any]) -> tuple[bool, str]:
        """Solve the component of ``uri`` (``/onefold/solve``; ``/solve``: the
        one ``request``'s ``pointer`` names) for ``request`` (its JSON,
        read): (solved, the answer's JSON).

        Raises:
            RequestError: a ``pointer`` that is not text.
            LookupError: no such component (its message: one line).
        """
        if uri == HopsDefault.SOLVE_ROUTE:
            pointer = request.get("pointer")
            if not isinstance(pointer, str):
                raise RequestError(
                    f"the request's pointer must name a component, got {pointer!r:.40}"
                )
            uri = pointer if pointer.startswith("/") else "/" + pointer
        comp = self._components.get(uri)
        if comp is None:
            raise LookupError(
                f"no Hops component {uri[:80]!r} (the server's: {', '.join(self.specs)})"
            )
        return self._process_request(comp, request)

    def _process_request(self, comp: HopsComponent, request: Mapping[str, Any]) -> tuple[bool, str]:
        spec = self.specs[comp.uri]
        try:
            values = read_values(spec.inputs, request.get("values", []))
            if values.get("template") is not None:  # a name, never a path the request makes up
                values["template"] = resolve_template(values["template"], self.template_dir)
            answer = spec.answer(values, request)
            outputs = [p.from_result(v) for p, v in zip(comp.outputs, answer.values, strict=True)]
            text = json.dumps({"values": outputs, "warnings": list(answer.warnings), "errors": []})
        except StaleInputsError as exc:  # 'Bad inputs' first: Hops rebuilds the component
            return False, json.dumps({"values": [], "errors": ["Bad inputs", str(exc)]})
        except (OneFoldError, UsageError) as exc:
            return False, error_answer(str(exc))
        except MemoryError as exc:  # a request the machine cannot afford: its answer, no crash
            text = memory_message(exc)
            print(f"onefold hops: {text}", file=sys.stderr)  # one line in the log, no traceback
            return False, error_answer(text)
        except Exception as exc:  # a bug: one line to Grasshopper, the traceback here
            traceback.print_exc(file=sys.stderr)
            return False, error_answer(
                f"internal error ({type(exc).__name__}: {exc}); the server's log has the traceback"
            )
        return True, text


def make_server(
    host: str = "127.0.0.1",
    port: int = 5000,
    template_dir: str | Path | None = None,
    allow_hosts: Sequence[str] = (),
) -> HopsServer:
    """A server of :class:`OneFoldHops` on ``host:port`` (0: any free port),
    bound but not yet serving (``serve_forever``).

    Args:
        template_dir: a folder whose ``.toml`` templates requests may name
            (by name; None: the shipped templates only).
        allow_hosts: more names the ``Host`` header may give (the machine's
            name on a network); its own address is always allowed, and the
            loopback names when it listens on a loopback address.
    """
    folder = None if template_dir is None else Path(template_dir).resolve()
    app = OneFoldHops(template_dir=folder)
    handler = type("Handler", (HopsHandler,), {"hops": app})
    server = HopsServer((host, port), handler)
    server.hosts = allowed_hosts(host, int(server.server_address[1]), allow_hosts)
    return server
