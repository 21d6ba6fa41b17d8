"""The layers of onefold_cad/layers.py hold: no import circle inside the
package, no module importing a layer above its own, in any form (module top,
inside a function, under TYPE_CHECKING), and the import-linter contract of
``make lint`` is the same list."""

from __future__ import annotations

import tomllib

import pytest

from onefold_cad.layers import LAYERS, ROOT, cycles, import_graph, layer_of, modules


@pytest.fixture(scope="module")
def graph():
    return import_graph()


def test_the_graph_sees_imports_in_functions_and_under_type_checking(graph):
    # the build context imports the flat pattern only inside a function,
    # and the design only under TYPE_CHECKING: both are edges
    edges = graph["onefold_cad.export.build_context"]
    assert "onefold_cad.fabrication.flat_pattern" in edges
    assert "onefold_cad.design" in edges


def test_no_import_circle_inside_the_package(graph):
    assert cycles(graph) == []


def test_a_planted_circle_is_found():
    planted = {"a": {"b": 1}, "b": {"c": 1}, "c": {"a": 1}, "d": {"a": 1}}
    assert cycles(planted) == [["a", "b", "c"]]


def test_every_module_belongs_to_a_layer():
    lost = [m for m in modules() if m != "onefold_cad" and layer_of(m) is None]
    assert lost == []


def test_no_module_imports_a_layer_above_its_own(graph):
    up = []
    for module, edges in graph.items():
        here = layer_of(module)
        if here is None:  # the package's public API names anything
            continue
        for target, line in edges.items():
            there = layer_of(target)
            assert there is not None, (module, target)
            if there[0] > here[0] or (there[0] == here[0] and there[1] != here[1]):
                up.append(f"{module}:{line} imports {target}")
    assert up == []


def test_the_lint_contract_is_the_layers():
    data = tomllib.loads((ROOT / "pyproject.toml").read_text())
    (contract,) = data["tool"]["importlinter"]["contracts"]
    assert contract["type"] == "layers"
    listed = [
        tuple(sorted(n.strip().strip("()") for n in row.split("|")))
        for row in reversed(contract["layers"])
    ]
    assert listed == [tuple(sorted(names)) for _, names in LAYERS]


def test_fit_sits_directly_above_the_layers_it_imports(graph):
    # inverse design is a computation on a design (its fold, resting form and
    # the part's rules), not a command: the CLI, the Hops server and scripts
    # call it, and nothing keeps a layer below the commands from calling it
    here = layer_of("onefold_cad.fit")
    below = [layer_of(t) for t in graph["onefold_cad.fit"]]
    assert here is not None and None not in below
    assert here[0] == max(i for i, _ in below) + 1
    assert LAYERS[here[0]][1] == ("onefold_cad.fit",)  # a row of its own
