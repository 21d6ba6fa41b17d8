"""The repository's shipped design templates, listed from templates/ itself
(independent of onefold_cad.templates' own listing): every *.toml but the
site files (site-*.toml, read by ``onefold site``)."""

from __future__ import annotations

from pathlib import Path

REPO_TEMPLATES = Path(__file__).resolve().parents[1] / "templates"

#: The design templates' names, sorted.
DESIGN_TEMPLATES = sorted(
    p.stem for p in REPO_TEMPLATES.glob("*.toml") if not p.stem.startswith("site-")
)
