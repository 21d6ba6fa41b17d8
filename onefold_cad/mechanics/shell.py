"""The shell model: a mesh with its material, reference form, rest curvature, creases
and gravity, and the layout of the unknowns.

The unknowns are one vector ``q`` of length ``mesh.n_dofs``: the current positions
``x`` (n, 3) node-major (``q[3 i + c]``), then the director angles (rad, see
``mesh`` for their numbering). Units: SI.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any, cast

import numpy as np
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import InvalidParameterError
from onefold_cad.mechanics.j2.layered import Plasticity, cartesian_map
from onefold_cad.mechanics.kinematics.transport import transported_director
from onefold_cad.mechanics.kinematics.triangles import face_metric
from onefold_cad.mechanics.material import ShellMaterial, strain_form
from onefold_cad.mechanics.mesh import SheetMesh

__all__ = [
    "REFERENCE_CACHES",
    "Shell",
    "director_angles",
    "directors",
    "moved",
    "hinge_stiffness",
    "flat_positions",
    "pack",
    "rigid_dofs",
    "unpack",
]

F = NDArray[np.float64]


#: Shell's cached properties, each a function of its mesh, material and
#: reference alone (``with_changes`` carries them over while those stay).
REFERENCE_CACHES = (
    "ref_metric", "ref_area", "form", "cartesian", "edge_frames", "edge_maps", "node_mass",
    "crease_length",
)  # fmt: skip


@dataclass(frozen=True, eq=False)
class Shell:
    """Everything the energies need besides the unknowns (build with ``Shell.create``).

    Attributes:
        mesh: the triangulation.
        material: E, nu, t, rho, sigma_y.
        reference: (n, 3) the stress-free positions of the membrane (m): the flat
            sheet, or the designed triangles.
        rest_curvature: (m, 3) the rest second fundamental form ``bbar`` per face,
            ``(b11, b12, b22)`` in the face's parametric coordinates (m).
        crease_angle: (kc,) set angle ``psi_set`` of each crease edge (rad, > 0 a
            valley: the faces' normals turn towards each other).
        crease_stiffness: (kc,) hinge stiffness ``k_c`` per unit length (N m/m per rad^2).
        gravity: (3,) acceleration (m/s^2), e.g. ``(0, 0, -9.80665)``.
        accumulated: (m,) or None: the faces' accumulated plastic curvature
            (1/m); with it bending follows the elastic-plastic law about the
            rest form (``plastic.moment``), without it bending is elastic.
        load: (N,) or None: external generalised forces on the unknowns (N on
            coordinates, N m on director angles), energy ``-load . q`` (a
            forming machine's grip, say).
        plasticity: None, or J2 plasticity through the thickness
            (:class:`~onefold_cad.mechanics.j2.layered.Plasticity`): membrane and
            bending of every face then follow the section's law from the
            faces' internal variables (``accumulated`` is not used with it).

    Director angles are measured about each edge from its reference director
    (``edge_frames``: made in the reference form, carried along the edge by
    parallel transport), so a clamp is an edge whose nodes and angle are held.
    """

    mesh: SheetMesh
    material: ShellMaterial
    reference: F
    rest_curvature: F
    crease_angle: F
    crease_stiffness: F
    gravity: F
    accumulated: F | None = None
    load: F | None = None
    plasticity: Plasticity | None = None

    @classmethod
    def create(
        cls,
        mesh: SheetMesh,
        material: ShellMaterial,
        *,
        reference: ArrayLike | None = None,
        rest_curvature: ArrayLike | None = None,
        crease_angle: ArrayLike = 0.0,
        crease_stiffness: ArrayLike | None = None,
        gravity: ArrayLike = (0.0, 0.0, 0.0),
    ) -> Shell:
        """A shell; defaults: flat reference, flat rest form, crease set angle 0 and
        stiffness ``hinge_stiffness(material, crease_angle)``, no gravity."""
        ref = flat_positions(mesh) if reference is None else np.array(reference, dtype=float)
        if ref.shape != (mesh.n_nodes, 3):
            raise InvalidParameterError("reference", f"needs shape ({mesh.n_nodes}, 3)")
        m, kc = mesh.n_faces, len(mesh.crease_edges)
        bbar = np.zeros((m, 3)) if rest_curvature is None else np.array(rest_curvature, float)
        angle = np.broadcast_to(np.asarray(crease_angle, dtype=float), (kc,)).copy()
        if crease_stiffness is None:
            stiff = hinge_stiffness(material, angle)
        else:
            stiff = np.broadcast_to(np.asarray(crease_stiffness, dtype=float), (kc,)).copy()
        return cls(
            mesh=mesh,
            material=material,
            reference=ref,
            rest_curvature=bbar.reshape(m, 3),
            crease_angle=angle,
            crease_stiffness=stiff,
            gravity=np.asarray(gravity, dtype=float).reshape(3),
        )

    def with_changes(self, **changes: Any) -> Shell:
        """A copy with some fields replaced (arrays are taken as given). While the
        mesh, material and reference stay, the copy keeps the quantities already
        derived from them (:data:`REFERENCE_CACHES`) instead of deriving them anew."""
        new = replace(self, **changes)
        if not changes.keys() & {"mesh", "material", "reference"}:
            for name in REFERENCE_CACHES:
                if name in self.__dict__:
                    new.__dict__[name] = self.__dict__[name]
        return new

    @cached_property
    def ref_metric(self) -> F:
        """(m, 3) reference metric ``abar`` (m^2)."""
        return face_metric(self.reference[self.mesh.triangles])[0]

    @cached_property
    def ref_area(self) -> F:
        """(m,) reference triangle areas ``Abar`` (m^2)."""
        a = self.ref_metric
        return 0.5 * np.sqrt(np.maximum(a[:, 0] * a[:, 2] - a[:, 1] ** 2, 0.0))

    @cached_property
    def form(self) -> F:
        """(m, 3, 3) the quadratic form ``K`` of the strain energies (``material.strain_form``)."""
        return strain_form(self.ref_metric, self.material.poisson)

    @cached_property
    def cartesian(self) -> F:
        """(m, 3, 3) each face's map from covariant strains to the Cartesian
        Voigt ones of its reference frame (``layered.cartesian_map``)."""
        return cartesian_map(self.ref_metric)

    @cached_property
    def edge_frames(self) -> tuple[F, F]:
        """(k, 3) each edge's reference direction ``t0`` and reference director ``r0``:
        the reference form's edge direction and the mean of its faces' normals there
        (normal to the edge)."""
        mesh, p = self.mesh, self.reference
        t0 = p[mesh.edges[:, 1]] - p[mesh.edges[:, 0]]
        t0 /= np.linalg.norm(t0, axis=1)[:, None]
        tri = p[mesh.triangles]
        normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        normal /= np.linalg.norm(normal, axis=1)[:, None]
        faces = mesh.edge_faces
        r0 = normal[faces[:, 0]] + np.where(faces[:, 1:] >= 0, normal[faces[:, 1]], 0.0)
        r0 -= np.einsum("ij,ij->i", r0, t0)[:, None] * t0
        return t0, r0 / np.linalg.norm(r0, axis=1)[:, None]

    @cached_property
    def edge_maps(self) -> F:
        """(m, 3, 4, 12) d(edge vector, director angle) of each face edge over the face's
        (9 coordinates, 3 director angles)."""
        mesh = self.mesh
        tri = mesh.triangles
        m = len(tri)
        out = np.zeros((m, 3, 4, 12))
        ends = mesh.edges[mesh.face_edges]
        rows = np.arange(m)
        for i in range(3):
            a_slot = np.argmax(tri == ends[:, i, 0, None], axis=1)
            b_slot = np.argmax(tri == ends[:, i, 1, None], axis=1)
            for c in range(3):
                out[rows, i, c, 3 * a_slot + c] = -1.0
                out[rows, i, c, 3 * b_slot + c] = 1.0
            out[:, i, 3, 9 + i] = 1.0
        return out

    @cached_property
    def node_mass(self) -> F:
        """(n,) lumped nodal masses ``rho t (adjacent reference area) / 3`` (kg)."""
        mat = self.material
        w = np.repeat(self.ref_area * mat.density * mat.thickness / 3.0, 3)
        return cast(
            "F", np.bincount(self.mesh.triangles.ravel(), weights=w, minlength=self.mesh.n_nodes)
        )

    @cached_property
    def crease_length(self) -> F:
        """(kc,) reference lengths of the crease edges (m)."""
        e = self.mesh.edges[self.mesh.crease_edges]
        return np.linalg.norm(self.reference[e[:, 1]] - self.reference[e[:, 0]], axis=1)

    @property
    def weight(self) -> float:
        """Total weight ``|g| * sum of masses`` (N)."""
        return float(np.linalg.norm(self.gravity) * self.node_mass.sum())


def hinge_stiffness(material: ShellMaterial, set_angle: ArrayLike, bend_radius: float = 0.0) -> F:
    """Hinge stiffness ``k_c = D / L_bend`` per unit length (N m/m per rad^2).

    ``L_bend = |psi_set| (r + t / 2)``, the bend zone's arc length at mid-thickness,
    floored at ``t``.
    """
    t = material.thickness
    length = np.maximum(np.abs(np.asarray(set_angle, dtype=float)) * (bend_radius + t / 2), t)
    return material.bending_stiffness / length


def director_angles(shell: Shell, x: ArrayLike, normals: ArrayLike) -> F:
    """(n_dir,) the director angles that put every edge's director along a given normal.

    Use it to impose a known smooth form: with the form's unit normals at the
    edge midpoints the faces' second fundamental forms are accurate to O(h^2).
    (Vertex positions alone leave free boundary directors, which an energy
    minimisation relaxes; for a form imposed as a whole they must be imposed too.)

    Args:
        shell: the model (its reference directors).
        x: (n, 3) node positions (m).
        normals: (n_dir, 3) the surface normal at each director's edge midpoint, on
            the side of that director's face (``T0``; a crease's second director:
            ``T1``), oriented like the faces' normals. Only the part normal to the
            edge is used.

    Raises:
        InvalidParameterError: an edge points against its reference direction.
    """
    mesh = shell.mesh
    p = np.asarray(x, dtype=float)
    d = np.asarray(normals, dtype=float).reshape(mesh.n_directors, 3)
    edge = np.concatenate([np.arange(mesh.n_edges), mesh.crease_edges])
    t0, r0 = shell.edge_frames
    vec = p[mesh.edges[edge, 1]] - p[mesh.edges[edge, 0]]
    if np.any(np.einsum("ij,ij->i", vec, t0[edge]) <= 0):
        raise InvalidParameterError("x", "an edge points against its reference direction")
    r = transported_director(t0[edge], r0[edge], vec, np.zeros(len(edge)), 0)[0]
    t = vec / np.linalg.norm(vec, axis=1)[:, None]
    return np.arctan2(np.einsum("ij,ij->i", np.cross(r, d), t), np.einsum("ij,ij->i", r, d))


def directors(shell: Shell, q: ArrayLike) -> F:
    """(n_dir, 3) the unit directors of a state (in the order of the director angles)."""
    mesh = shell.mesh
    x, angles = unpack(mesh, q)
    edge = np.concatenate([np.arange(mesh.n_edges), mesh.crease_edges])
    t0, r0 = shell.edge_frames
    vec = x[mesh.edges[edge, 1]] - x[mesh.edges[edge, 0]]
    return transported_director(t0[edge], r0[edge], vec, angles, 0)[0]


def moved(
    shell: Shell, q: ArrayLike, rotation: ArrayLike, translation: ArrayLike
) -> tuple[Shell, F]:
    """The shell and its state ``q`` moved rigidly together, ``x -> rotation @ x +
    translation``.

    The reference form moves with the state, so every edge's reference frame
    (``Shell.edge_frames``) turns with it and the director angles, measured from
    directors transported along each edge from that frame, keep their values:
    the moved state has the same energy, directors and stresses. (Moving the
    state alone would measure its directors from the unmoved reference, whose
    transport has no meaning for an edge turned 90 deg or more: a long sheet
    stood on its side turns that far.)

    Returns:
        The moved shell (its reference moved; the other fields as given) and the
        moved state, to be used together.
    """
    rot = np.asarray(rotation, dtype=float)
    shift = np.asarray(translation, dtype=float)
    x, angles = unpack(shell.mesh, q)
    placed = shell.with_changes(reference=shell.reference @ rot.T + shift)
    return placed, pack(x @ rot.T + shift, angles)


def flat_positions(mesh: SheetMesh) -> F:
    """(n, 3) the flat sheet's node positions (z = 0)."""
    return np.column_stack([mesh.nodes, np.zeros(mesh.n_nodes)])


def pack(x: ArrayLike, directors: ArrayLike) -> F:
    """One unknown vector from (n, 3) positions and (n_dir,) director angles."""
    return np.concatenate(
        [np.asarray(x, dtype=float).ravel(), np.asarray(directors, float).ravel()]
    )


def unpack(mesh: SheetMesh, q: ArrayLike) -> tuple[F, F]:
    """(n, 3) positions and (n_dir,) director angles of an unknown vector (views)."""
    q = np.asarray(q, dtype=float)
    n = mesh.n_nodes
    if q.shape != (mesh.n_dofs,):
        raise InvalidParameterError("q", f"needs shape ({mesh.n_dofs},), got {q.shape}")
    return q[: 3 * n].reshape(n, 3), q[3 * n :]


def rigid_dofs(x: ArrayLike, nodes: tuple[int, int, int] | None = None) -> NDArray[np.int64]:
    """A minimal (3-2-1) restraint of rigid motions: the DOF ids to fix.

    Node ``i`` is fixed in x, y and z; node ``j`` in the two axes least aligned
    with ``j - i``; node ``k`` in the axis most aligned with the normal of the
    plane ``i j k``. By default ``i, j`` are far apart and ``k`` is the node
    farthest from their line.

    Args:
        x: (n, 3) the current positions (m).
        nodes: the three nodes, or None to choose them.
    """
    p = np.asarray(x, dtype=float)
    if nodes is None:
        i = int(np.argmin(p[:, 0] + p[:, 1]))
        j = int(np.argmax(np.linalg.norm(p - p[i], axis=1)))
        k = int(np.argmax(np.linalg.norm(np.cross(p - p[i], p[j] - p[i]), axis=1)))
        nodes = (i, j, k)
    i, j, k = nodes
    d = p[j] - p[i]
    normal = np.cross(d, p[k] - p[i])
    along = int(np.argmax(np.abs(d)))
    fixed = [3 * i, 3 * i + 1, 3 * i + 2]
    fixed += [3 * j + c for c in range(3) if c != along]
    fixed.append(3 * k + int(np.argmax(np.abs(normal))))
    return np.array(fixed, dtype=np.int64)
