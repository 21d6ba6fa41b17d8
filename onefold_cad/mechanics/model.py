"""A design as a mechanics model: its flat sheet meshed, its material in SI
units, its designed form, and where it stands.

:func:`sheet_model` is the one place a :class:`~onefold_cad.design.Design`
enters the mechanics: everything after it (the forming sequence, the
stresses, the deviations) works on the :class:`SheetModel`'s plain arrays in
metres, newtons and pascals. ``scale`` turns the design's lengths into metres.

The mesh conforms to the outline, the relief hole (a polygon) and both crease
halves (from the hole to the sheet's edge), and has a node at each of the
designed form's ground contacts; it is graded from a fraction of the hole's
radius at the apex (where the cones' curvature k / r is largest) to
``h_max`` (:data:`MESH_LEVELS`, a fraction of the sheet's size) away from it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from onefold_cad.choices import Crease, Law, MeshLevel, Model
from onefold_cad.design import Design, rest_once
from onefold_cad.errors import InvalidParameterError
from onefold_cad.fabrication.relief_hole import relief_hole_diameter, solid_min_relief_hole
from onefold_cad.fabrication.rules import PLAUSIBLE_DENSITY
from onefold_cad.geometry.checks import shown
from onefold_cad.geometry.folding import FoldedSheet
from onefold_cad.geometry.material import Material
from onefold_cad.geometry.numeric import Array
from onefold_cad.geometry.resting.placement import RestingPlacement
from onefold_cad.mechanics.energy import second_fundamental_form
from onefold_cad.mechanics.material import ShellMaterial
from onefold_cad.mechanics.mesh import SheetMesh, mesh_sheet
from onefold_cad.mechanics.shell import Shell, director_angles, hinge_stiffness

__all__ = [
    "CREASES",
    "HELD_STIFFNESS",
    "MESH_GRADING",
    "MESH_LEVELS",
    "SheetModel",
    "FINER",
    "check_cone_forming",
    "check_simulable",
    "director_normals",
    "sheet_model",
    "shell_material",
]

#: The mesh's largest edge for each ``--mesh`` level, relative to the sheet's size
#: (``Sheet.size``: the largest distance from H to the sheet's edge).
MESH_LEVELS = {MeshLevel.COARSE: 1 / 8, MeshLevel.NORMAL: 1 / 20, MeshLevel.FINE: 1 / 40}
#: Edge length at the relief hole's rim relative to its radius, and how fast it grows
#: with the distance from the apex.
_RIM, _GROWTH = 0.6, 0.25
#: How much coarser each level grades from the hole (its rim size and growth
#: times this): the coarse preview grades 1.5x faster (856 nodes for
#: patkau-one-fold instead of 1 729, half the time, its standing and released
#: deviations within 0.5 % of the normal mesh's where the 1 729-node mesh was
#: within 0.9 %).
MESH_GRADING = {MeshLevel.COARSE: 1.5, MeshLevel.NORMAL: 1.0, MeshLevel.FINE: 1.0}
#: The crease models: ``held`` keeps each crease half at its set angle (a hinge
#: :data:`HELD_STIFFNESS` times stiffer than a bend zone one thickness long), as a
#: shell FE model's welded fold line does; ``elastic`` gives it the bend zone's own
#: stiffness D / L_bend (``hinge_stiffness``).
CREASES = tuple(c.value for c in Crease)
HELD_STIFFNESS = 1e4
#: Standard gravity (m/s^2).
GRAVITY = 9.80665


@dataclass(frozen=True, eq=False)
class SheetModel:
    """A design ready for the mechanics (SI units).

    Attributes:
        mesh: the flat sheet's triangulation (m).
        shell: the elastic shell of the designed form (membrane reference and
            rest curvature: the designed triangles; crease set angles; no
            gravity): the stages change its rest curvature and gravity.
        designed: ``(n, 3)`` the nodes on the designed form, fold frame (m).
        normals: ``(n_dir, 3)`` the designed form's unit top normal at each
            director's edge midpoint, on that director's side.
        material: E, nu, t, rho, sigma_y.
        contacts: ``(c,)`` the nodes on the designed resting contacts.
        rest: the designed form's resting placement (the zero-thickness
            sheet's), in the design's unit.
        scale: metres per design unit.
        hole_radius: the relief hole's radius (m).
        h_max: the mesh's largest target edge (m).
        crease: the crease model (:data:`CREASES`).
        cones_compensated: the cones are formed past their springback (the
            material's ``cone_forming``; the J2 forming reads it).
    """

    mesh: SheetMesh
    shell: Shell
    designed: Array
    normals: Array
    material: ShellMaterial
    contacts: np.ndarray
    rest: RestingPlacement
    scale: float
    hole_radius: float
    h_max: float
    crease: str
    cones_compensated: bool = False

    @property
    def size(self) -> float:
        """The sheet's size (m): its largest distance from H."""
        return float(np.max(np.hypot(self.mesh.nodes[:, 0], self.mesh.nodes[:, 1])))

    @property
    def weight_N(self) -> float:
        """The sheet's weight (N) under standard gravity."""
        return float(GRAVITY * self.shell.node_mass.sum())

    def standing_frame(self) -> tuple[Array, Array]:
        """The designed resting placement as ``(rotation, translation)`` in metres."""
        return self.rest.rotation, self.rest.translation * self.scale


def _required(value: float | None, name: str, what: str, flag: str) -> float:
    if value is None:
        raise InvalidParameterError(
            name,
            f"simulate needs the material's {what}: set {flag} or the template's material.{name}",
        )
    return float(value)


def shell_material(design: Design, yield_stress_MPa: float | None = None) -> ShellMaterial:
    """The design's material in SI units (``yield_stress_MPa`` overrides its
    yield stress).

    Raises:
        InvalidParameterError: a value simulate needs is missing (named), the
            sheet has no thickness, or the yield stress exceeds the modulus.
    """
    m = design.material
    if m.thickness <= 0.0:
        raise InvalidParameterError(
            "thickness", "simulate needs a sheet with thickness > 0 (the design has none)"
        )
    e = _required(m.youngs_modulus, "youngs_modulus", "Young's modulus", "--youngs-modulus GPA")
    nu = _required(m.poisson, "poisson", "Poisson's ratio", "--poisson NU")
    sy = _required(m.yield_stress, "yield_stress", "yield stress", "--yield-stress MPA")
    rho = _required(m.density, "density", "density", "--density KG/M3")
    lo, hi = PLAUSIBLE_DENSITY
    if not lo <= rho <= hi:  # the stages' force tolerances are relative to the weight
        raise InvalidParameterError(
            "density",
            f"simulate needs a sheet material's density, {lo:g} to {hi:g} kg/m^3 (its force "
            f"tolerances are relative to the sheet's weight), got {shown(rho)}",
        )
    sy = sy if yield_stress_MPa is None else yield_stress_MPa
    metres = design.units.mm / 1000.0
    h = 0.0 if m.hardening_modulus is None else m.hardening_modulus * 1e6
    kin = 0.0 if m.kinematic_hardening is None else m.kinematic_hardening
    return ShellMaterial(e * 1e9, nu, m.thickness * metres, rho, sy * 1e6, (1.0 - kin) * h, kin * h)


def check_simulable(design: Design) -> None:
    """Check that ``design`` can be simulated whatever its fold (a sweep asks
    before any design runs; :func:`sheet_model` also checks the relief hole,
    which the fold sizes).

    Raises:
        InvalidParameterError: the paper model, no thickness or a missing
            elastic value (named, with the flag that sets it).
    """
    if design.model is not Model.EXACT:
        raise InvalidParameterError(
            "model",
            "simulate needs the exact model (--model exact): the paper's fan has no "
            "smooth surface to bend",
        )
    shell_material(design)


def _hole_radius(design: Design, folded: FoldedSheet) -> float:
    """The radius (design unit) of the relief hole the sheet is meshed around:
    the one every export cuts, at least the smallest a sheet of its thickness
    takes without overlapping itself around H (where the cones' curvature
    grows without bound, the solid's smallest hole)."""
    d = relief_hole_diameter(design, folded)
    if d <= 0.0:
        raise InvalidParameterError(
            "relief_hole",
            "simulate needs a relief hole > 0 at the apex (the cones' curvature grows "
            "without bound at H); set --relief-hole",
        )
    try:
        need = solid_min_relief_hole(folded, design.material)
    except InvalidParameterError:  # no mitre (a flat fold): nothing overlaps at H
        need = 0.0
    if d < need:
        u = design.units.value
        raise InvalidParameterError(
            "relief_hole",
            f"simulate needs a relief hole of at least {need:.4g} {u}, the smallest a sheet "
            f"{design.material.thickness:g} {u} thick takes without overlapping itself around "
            f"H, got {shown(d)} {u}",
        )
    return 0.5 * d


def director_normals(folded: FoldedSheet, mesh: SheetMesh, scale: float) -> Array:
    """``(n_dir, 3)`` the top normal of ``folded``'s form (the design, or any
    form of the same flat sheet) at each director's edge midpoint of ``mesh``
    (flat nodes in m; ``scale``: metres per design unit), on the side of its
    face: sampled a millionth of the edge towards the face's centroid, so a
    crease's two directors get their own side's normal."""
    edge = np.concatenate([np.arange(mesh.n_edges), mesh.crease_edges])
    face = np.concatenate([mesh.edge_faces[:, 0], mesh.edge_faces[mesh.crease_edges, 1]])
    mid = 0.5 * (mesh.nodes[mesh.edges[edge, 0]] + mesh.nodes[mesh.edges[edge, 1]])
    centre = mesh.nodes[mesh.triangles[face]].mean(axis=1)
    return folded.normals((mid + 1e-6 * (centre - mid)) / scale)


def _crease_angles(folded: FoldedSheet, mesh: SheetMesh, material: Material) -> Array:
    """``(kc,)`` each crease edge's set angle (rad; > 0 where the bend is UP, the
    top faces turning towards each other): its crease half's fold angle plus
    the material's crease overbend (:meth:`Material.crease_set_angle`).

    Raises:
        InvalidParameterError: a half's set angle outside (0, 180) deg.
    """
    plus, minus = folded.crease
    x = mesh.nodes[mesh.edges[mesh.crease_edges]].mean(axis=1)[:, 0]
    out = np.empty(len(x))
    for half, where in ((plus, x > 0.0), (minus, x <= 0.0)):
        sign = 1.0 if half.bend == "UP" else -1.0
        angle = material.crease_set_angle(half.fold_angle_deg)
        if not 0.0 < angle < 180.0:
            raise InvalidParameterError(
                "crease_overbend", f"{material.crease_overbend:g} deg sets crease half {half.name} "
                f"({half.fold_angle_deg:.4g} deg) to {angle:.4g} deg: the set angle must be "
                "above 0 and below 180 deg"
            )  # fmt: skip
        out[where] = sign * math.radians(angle)
    return out


def _contact_points(folded: FoldedSheet, rest: RestingPlacement, gap: float) -> Array:
    """``(c, 2)`` the flat points of the designed resting contacts, one of each
    cluster closer than ``gap`` (design unit).

    A sheet that rests along a stretch of its edge has contacts a few
    micrometres apart (patkau-one-fold at 4000 x 1000 mm: two 0.016 mm apart):
    as mesh nodes they force edges that short (14 um), whose round-off in the
    membrane forces (1.6e-3 N) is above Newton's tolerance, and the standing
    stalls at no load. The first of such a cluster stands for it (the others lie
    closer to it than the mesh's finest edge, so the contact is the same).
    """
    back = (rest.contacts - rest.translation) @ rest.rotation  # to the fold frame
    points = folded.unfold(back)[0]
    kept: list[Array] = []
    for p in points:
        if all(np.hypot(*(p - k)) >= gap for k in kept):
            kept.append(p)
    return np.array(kept).reshape(-1, 2)


#: The convergence check's mesh: every edge length divided by this (twice the nodes).
FINER = math.sqrt(2.0)


def check_cone_forming(design: Design, law: str, reference: str) -> None:
    """Refuse cones formed past their springback (``cone_forming =
    "compensated"``) with the moment law: only the J2 section's springback
    is inverted (:mod:`onefold_cad.mechanics.j2.springback`).

    Raises:
        InvalidParameterError: naming ``cone_forming``.
    """
    if design.material.cones_compensated and reference == "flat" and law != Law.J2.value:
        raise InvalidParameterError(
            "cone_forming",
            f"'compensated' forms the cones past the J2 law's springback; with --law {law} "
            "use --law j2 (or --cone-forming design)",
        )


def sheet_model(
    design: Design,
    folded: FoldedSheet,
    *,
    h_max: float | None = None,
    level: str = "normal",
    crease: str = "held",
    yield_stress_MPa: float | None = None,
    refine: float = 1.0,
) -> SheetModel:
    """The mechanics model of ``design`` and its fold.

    Args:
        design: the design (exact model, thickness, elastic data).
        folded: ``fold_design(design)``.
        h_max: the mesh's largest edge (m); None: ``level``'s.
        level: 'coarse', 'normal' or 'fine' (:data:`MESH_LEVELS`).
        crease: 'held' or 'elastic' (:data:`CREASES`).
        yield_stress_MPa: overrides the material's yield stress.
        refine: every target edge length (at the hole, its growth, the
            largest) divided by this (:data:`FINER` for the convergence check).

    Raises:
        InvalidParameterError: the paper model, no thickness, no relief hole,
            a missing elastic value, an unknown level or crease model.
    """
    check_simulable(design)
    level = MeshLevel.parse(level)
    crease = Crease.parse(crease).value
    material = shell_material(design, yield_stress_MPa)
    scale = design.units.mm / 1000.0
    hole = _hole_radius(design, folded) * scale
    rest = rest_once(folded)
    size = design.sheet.size * scale
    h = MESH_LEVELS[level] * size if h_max is None else float(h_max)
    grading = MESH_GRADING[level] if h_max is None else 1.0
    creases = [
        ((math.copysign(hole, c.end_flat[0]), 0.0), tuple(c.end_flat * scale))
        for c in folded.crease
    ]
    h_min = grading * _RIM * hole / refine
    mesh = mesh_sheet(
        design.sheet.vertices * scale,
        size=(h_min, grading * _GROWTH / refine, h / refine),
        hole_radius=hole,
        creases=creases,
        boundary_points=_contact_points(folded, rest, h_min / scale) * scale,
    )
    designed = folded.map_points(mesh.nodes / scale) * scale
    normals = director_normals(folded, mesh, scale)
    angles = _crease_angles(folded, mesh, design.material)
    if crease == "held":
        stiffness = np.full(
            len(angles), HELD_STIFFNESS * material.bending_stiffness / material.thickness
        )
    else:
        stiffness = hinge_stiffness(material, angles, design.material.bend_radius * scale)
    shell = Shell.create(
        mesh, material, reference=designed, crease_angle=angles, crease_stiffness=stiffness
    )
    placed = designed @ rest.rotation.T + rest.translation * scale
    contacts = np.flatnonzero(placed[:, 2] <= 1e-9 * size)
    return SheetModel(
        mesh=mesh,
        shell=shell.with_changes(rest_curvature=_designed_curvature(shell, designed, normals)),
        designed=designed,
        normals=normals,
        material=material,
        contacts=contacts,
        rest=rest,
        scale=scale,
        hole_radius=hole,
        h_max=h / refine,
        crease=crease,
        cones_compensated=design.material.cones_compensated,
    )


def _designed_curvature(shell: Shell, designed: Array, normals: Array) -> Array:
    """``(m, 3)`` the designed form's second fundamental form per face, from its
    nodes and the directors along its normals."""
    q = np.concatenate([designed.ravel(), director_angles(shell, designed, normals)])
    return second_fundamental_form(shell, q)
