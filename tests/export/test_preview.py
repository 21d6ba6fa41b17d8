"""The 3D preview PNG of the folded form."""

from __future__ import annotations

import struct
import subprocess
import sys

import numpy as np
import pytest

from onefold_cad import Design, ExportError, FrameCurve, Sheet, build_design
from onefold_cad.export.preview import render_folded_preview, resting_mesh


@pytest.fixture(scope="module")
def folded():
    return build_design(Design("p", FrameCurve(40, 40), Sheet.rectangle(300, 200, 0.5)))


def _png_size(data: bytes) -> tuple[int, int]:
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    assert data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def test_resting_mesh_stands_on_the_ground(folded):
    verts, faces = resting_mesh(folded, angular=30, radial=4)
    size = folded.sheet.size
    assert verts[:, 2].min() == pytest.approx(0.0, abs=1e-9 * size)
    assert faces.min() >= 0 and faces.max() < len(verts)
    # A rigid motion of the folded mesh: distances from the apex survive.
    raw, _ = folded.mesh(angular=30, radial=4)
    apex = folded.resting.apply(folded.apex[None, :])[0]
    np.testing.assert_allclose(
        np.linalg.norm(verts - apex, axis=1),
        np.linalg.norm(raw - folded.apex, axis=1),
        atol=1e-9 * size,
    )


def test_render_writes_a_png_of_the_requested_size(tmp_path, folded):
    out = render_folded_preview(folded, tmp_path / "p-3d.png", title="p", size_px=(400, 300))
    data = out.read_bytes()
    assert _png_size(data) == (400, 300)
    assert [p.name for p in tmp_path.iterdir()] == ["p-3d.png"]
    import matplotlib.image as mpimg

    img = mpimg.imread(out)[:, :, :3]
    # Not blank: the warm top face or the cool bottom face shows somewhere.
    warm = (img[:, :, 0] - img[:, :, 2]) > 0.15
    cool = (img[:, :, 2] - img[:, :, 0]) > 0.08
    assert warm.sum() + cool.sum() > 0.02 * img.shape[0] * img.shape[1]


def test_render_failure_raises_export_error_and_leaves_nothing(tmp_path, folded):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(ExportError):
        render_folded_preview(folded, blocker / "p.png")
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


def test_matplotlib_is_imported_only_by_the_preview():
    code = (
        "import sys, onefold_cad, onefold_cad.cli, onefold_cad.export.preview, "
        "onefold_cad.export.report; print('matplotlib' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
