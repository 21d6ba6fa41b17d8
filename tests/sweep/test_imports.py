"""Heavy libraries are imported where they are used: pyarrow by the sweep's
tables, dask by its cluster backend, scipy's samplers by the samplers, and
matplotlib by the export adapters only; the sweep's parser needs no numpy."""

from __future__ import annotations

import ast
import json
import subprocess
import sys

from onefold_cad.layers import modules

ONLY_IN = {
    "pyarrow": {"onefold_cad.sweep.tables"},
    "dask": {"onefold_cad.sweep.backends"},
    "distributed": {"onefold_cad.sweep.backends"},
    "scipy.stats": {"onefold_cad.sweep.samplers"},
}


def _imports(path):
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            yield from (a.name for a in node.names)
        elif isinstance(node, ast.ImportFrom) and not node.level:
            yield node.module or ""


def test_heavy_libraries_are_imported_by_their_one_module():
    found = {lib: set() for lib in ONLY_IN}
    for name, path in modules().items():
        for mod in _imports(path):
            for lib in ONLY_IN:
                if mod == lib or mod.startswith(lib + "."):
                    found[lib].add(name)
    assert all(found[lib] <= allowed for lib, allowed in ONLY_IN.items()), found
    assert found["pyarrow"] and found["dask"] and found["scipy.stats"]


def test_the_sweep_s_modules_import_matplotlib_only_through_export():
    for name, path in modules().items():
        if name.startswith("onefold_cad.sweep"):
            assert not any(m.startswith("matplotlib") for m in _imports(path)), name


def test_sweep_help_and_solve_load_no_table_or_cluster_library():
    code = (
        "import io, contextlib, json, sys\n"
        "from onefold_cad.cli.main import main\n"
        "rcs = []\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    rcs.append(main(['sweep', '--help']))\n"
        "    help_modules = sorted(sys.modules)\n"
        "    rcs.append(main(['solve']))\n"
        "print(json.dumps([rcs, help_modules, sorted(sys.modules)]))\n"
    )
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True)
    rcs, help_modules, solve_modules = json.loads(proc.stdout.splitlines()[-1])
    assert rcs == [0, 0], proc.stderr
    assert "numpy" not in help_modules
    heavy = ("pyarrow", "dask", "distributed", "scipy.stats", "matplotlib")
    assert [m for m in solve_modules if m.split(".")[0] in heavy or m == "scipy.stats"] == []


def test_a_pool_with_thumbnails_starts_its_workers_with_matplotlib_loaded():
    """The forkserver imports what a thumbnail draws with when the sweep has
    thumbnails (each worker then skips its own ~1.5 s import), and only then;
    the preloaded module brings matplotlib's canvas, 3D axes and the preview."""
    code = (
        "import json, sys, multiprocessing.forkserver as fs\n"
        "from onefold_cad.sweep import backends\n"
        "backends._context(images=False)\n"
        "without = list(fs._forkserver._preload_modules)\n"
        "backends._context(images=True)\n"
        "with_images = list(fs._forkserver._preload_modules)\n"
        "import onefold_cad.export.pictures.preload\n"
        "names = ['matplotlib.backends.backend_agg', 'mpl_toolkits.mplot3d',\n"
        "         'onefold_cad.export.pictures.surface_image']\n"
        "print(json.dumps([without, with_images, [n in sys.modules for n in names]]))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    without, with_images, loaded = json.loads(out.stdout)
    assert without == ["onefold_cad.sweep.evaluate"]
    assert with_images == ["onefold_cad.sweep.evaluate", "onefold_cad.export.pictures.preload"]
    assert all(loaded)
