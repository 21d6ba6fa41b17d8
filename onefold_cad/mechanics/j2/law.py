"""Plane-stress J2 (von Mises) plasticity with linear isotropic and kinematic
hardening: the return mapping at material points, its consistent tangent and
its incremental energy.

Vectors are in Voigt form on an orthonormal frame of the sheet's plane:
stresses ``(s11, s22, s12)`` (Pa), strains ``(e11, e22, g12)`` with the
engineering shear ``g12 = 2 e12``. The law (Simo and Hughes, *Computational
Inelasticity*, 1998, sections 2.3 and 3.4; Simo and Taylor 1986):

- elastic: ``sigma = C (eps - eps_p)``, ``C`` the plane-stress stiffness;
- yield: ``f = xi^T P xi / 2 - kappa^2 / 3 <= 0`` with ``xi = sigma - beta``
  (``xi^T P xi = 2/3 sigma_vm^2``), ``kappa = sigma_y + H_iso alpha``;
- flow (normality): ``d eps_p = dgamma P xi``; the equivalent plastic strain
  grows by ``sqrt(2/3) dgamma sqrt(xi^T P xi)``; the back stress (the
  plane-stress image of the 3D deviatoric back stress ``2/3 H_kin eps_p``)
  by ``2/3 H_kin dgamma xi``.

In uniaxial stress this is ``sigma = sigma_y + (H_iso + H_kin) eps_p``; with
``H_kin`` alone a reversal yields again after a stress change of
``2 sigma_y`` (Bauschinger). The backward-Euler update is the closest-point
projection (:func:`update`): one scalar equation in ``dgamma``, solved by
Newton's method in the frame where ``C`` and ``P`` are both diagonal. It is
the minimiser of an incremental energy (elastic + hardening energy +
dissipation ``sigma_y`` times the plastic strain increment), whose gradient
is the stress and whose Hessian is the consistent tangent (symmetric), so a
structure's equilibrium in one load increment is an energy minimum and
Newton's method on it converges quadratically.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from onefold_cad.errors import ConvergenceError, InvalidParameterError
from onefold_cad.mechanics.material import ShellMaterial, check_hardening

__all__ = ["P", "J2Law", "J2Response", "J2State", "elastic_matrix", "update", "von_mises"]

F = NDArray[np.float64]

#: ``xi^T P xi = 2/3 sigma_vm^2`` for a plane stress ``xi``; ``P xi`` the flow direction.
P = np.array([[2.0, -1.0, 0.0], [-1.0, 2.0, 0.0], [0.0, 0.0, 6.0]]) / 3.0
#: The orthonormal frame in which ``P`` and ``C`` are both diagonal (columns).
_Q = np.array([[1.0, 1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 0.0, math.sqrt(2.0)]]) / math.sqrt(2.0)
_P_EIGEN = np.array([1.0 / 3.0, 1.0, 2.0])
#: Tolerance of the consistency condition, relative to the yield stress.
TOLERANCE = 1e-12
#: Newton (bisection-guarded) iterations of the return mapping's scalar equation.
MAX_ITERATIONS = 100


@dataclass(frozen=True)
class J2Law:
    """A plane-stress von Mises material with linear hardening.

    Attributes:
        youngs_modulus: E (Pa).
        poisson: nu, in (-1, 0.5).
        yield_stress: sigma_y (Pa), ``inf`` for an elastic material.
        hardening_iso: isotropic hardening modulus H_iso >= 0 (Pa): the yield
            stress grows by it times the equivalent plastic strain.
        hardening_kin: kinematic hardening modulus H_kin >= 0 (Pa): the
            centre of the yield surface moves (Bauschinger effect).
    """

    youngs_modulus: float
    poisson: float
    yield_stress: float
    hardening_iso: float = 0.0
    hardening_kin: float = 0.0

    def __post_init__(self) -> None:
        if not (math.isfinite(self.youngs_modulus) and self.youngs_modulus > 0):
            raise InvalidParameterError(
                "youngs_modulus", f"must be finite and > 0, got {self.youngs_modulus!r}"
            )
        if not -1.0 < self.poisson < 0.5:
            raise InvalidParameterError("poisson", f"must lie in (-1, 0.5), got {self.poisson!r}")
        if not self.yield_stress > 0:
            raise InvalidParameterError("yield_stress", f"must be > 0, got {self.yield_stress!r}")
        check_hardening(self.hardening_iso, self.hardening_kin)

    @classmethod
    def of(cls, material: ShellMaterial) -> J2Law:
        """The law of a sheet's ``material`` (its E, nu, sigma_y and hardening)."""
        m = material
        return cls(m.youngs_modulus, m.poisson, m.yield_stress, m.hardening_iso, m.hardening_kin)

    @property
    def plane_modulus(self) -> float:
        """E' = E / (1 - nu^2) (Pa)."""
        return self.youngs_modulus / (1.0 - self.poisson**2)

    @property
    def c_eigen(self) -> F:
        """(3,) the eigenvalues of ``C`` on ``P``'s eigenvectors: E / (1 - nu),
        E / (1 + nu) and G = E / (2 (1 + nu)) (Pa)."""
        e, nu = self.youngs_modulus, self.poisson
        return np.array([e / (1.0 - nu), e / (1.0 + nu), e / (2.0 * (1.0 + nu))])


def elastic_matrix(law: J2Law) -> F:
    """(3, 3) the plane-stress stiffness ``C`` (Pa) for Voigt strains with engineering shear."""
    ep, nu = law.plane_modulus, law.poisson
    return ep * np.array([[1.0, nu, 0.0], [nu, 1.0, 0.0], [0.0, 0.0, (1.0 - nu) / 2.0]])


def von_mises(stress: F) -> F:
    """The von Mises stress (Pa) of plane stresses ``(..., 3)``."""
    s = np.asarray(stress, dtype=float)
    s11, s22, s12 = s[..., 0], s[..., 1], s[..., 2]
    return np.sqrt(np.maximum(s11**2 - s11 * s22 + s22**2 + 3.0 * s12**2, 0.0))


@dataclass(frozen=True)
class J2State:
    """The internal variables of material points (any leading shape ``S``).

    Attributes:
        plastic_strain: ``S + (3,)`` eps_p (Voigt, engineering shear).
        back_stress: ``S + (3,)`` beta (Pa), the plane-stress image of the back stress.
        equivalent: ``S`` the accumulated equivalent plastic strain alpha.
    """

    plastic_strain: F
    back_stress: F
    equivalent: F

    @classmethod
    def virgin(cls, shape: tuple[int, ...]) -> J2State:
        """Points never strained plastically."""
        return cls(np.zeros(shape + (3,)), np.zeros(shape + (3,)), np.zeros(shape))


@dataclass(frozen=True)
class J2Response:
    """The response of material points to total strains from a state.

    Attributes:
        stress: ``S + (3,)`` (Pa).
        tangent: ``S + (3, 3)`` the consistent tangent d stress / d strain (Pa).
        energy: ``S`` the incremental energy density (J/m^3) whose gradient is
            the stress (defined up to a constant per point).
        state: the internal variables after the step.
        plastic: ``S`` bool, the points that flowed in this step.
    """

    stress: F
    tangent: F
    energy: F
    state: J2State
    plastic: NDArray[np.bool_]


def _kinematic_energy(law: J2Law, eps_p: F) -> F:
    """``H_kin / 3 eps_p : eps_p`` (3D tensor norm, ``eps_p33 = -(eps_p11 + eps_p22)``)."""
    e11, e22, g12 = eps_p[..., 0], eps_p[..., 1], eps_p[..., 2]
    return law.hardening_kin / 3.0 * (e11**2 + e22**2 + (e11 + e22) ** 2 + g12**2 / 2.0)


def _gamma(law: J2Law, xt: F, alpha: F) -> F:
    """``dgamma`` of the closest-point projection, for the trial ``xi`` in ``P``'s
    frame ``xt`` (k, 3) and the accumulated plastic strain ``alpha`` (k,).

    With ``phi(dgamma) = sqrt(xi^T P xi)`` and ``T = sqrt(2/3) kappa_n``, the
    consistency condition ``phi = sqrt(2/3) kappa(alpha_n + sqrt(2/3) dgamma
    phi)`` is ``phi (1 - 2/3 H_iso dgamma) = T``, solved as ``h(dgamma) = (1 -
    2/3 H_iso dgamma) / T - 1 / phi = 0``: ``1 / phi`` is linear in ``dgamma``
    where the trial is along one of ``P``'s eigenvectors (equibiaxial stress,
    in-plane pure shear: one Newton step is exact) and nearly so elsewhere, so
    Newton's method from 0 takes 3 or 4 steps where on ``phi - sqrt(2/3)
    kappa`` it took about 10. Converged when ``|phi - sqrt(2/3) kappa| = |h|
    phi T <= TOLERANCE T``.
    """
    sy, hi, hk = law.yield_stress, law.hardening_iso, law.hardening_kin
    a = 2.0 / 3.0 * hk + law.c_eigen * _P_EIGEN  # xi_i = xt_i / (1 + dgamma a_i)
    pa = -2.0 * _P_EIGEN * a
    target = math.sqrt(2.0 / 3.0) * (sy + hi * alpha)
    c_hi = 2.0 / 3.0 * hi

    def h(dg: F, xt: F, tgt: F) -> tuple[F, F, F]:
        den = 1.0 + dg[:, None] * a
        xi = xt / den
        phi2 = xi**2 @ _P_EIGEN
        phi = np.sqrt(phi2)
        dphi = ((xi**2 / den) @ pa) / (2.0 * phi)
        return (1.0 - c_hi * dg) / tgt - 1.0 / phi, -c_hi / tgt + dphi / phi2, phi

    # h(0) > 0 and h falls monotonically (1 / phi grows): Newton within the
    # bracket [lo, up] of the signs seen, bisecting where a step leaves it (up
    # is infinite until a step overshoots); each pass works on the points not
    # yet converged only.
    k = len(xt)
    dg, lo, up = np.zeros(k), np.zeros(k), np.full(k, np.inf)
    todo = np.arange(k)
    for _ in range(MAX_ITERATIONS):
        val, der, phi = h(dg[todo], xt[todo], target[todo])
        lo_t = np.where(val > 0, dg[todo], lo[todo])
        up_t = np.where(val <= 0, dg[todo], up[todo])
        lo[todo], up[todo] = lo_t, up_t
        closed = np.isfinite(up_t) & (up_t - lo_t <= 1e-15 * up_t)
        done = (np.abs(val) * phi <= TOLERANCE) | closed
        if np.all(done):
            return dg
        with np.errstate(divide="ignore", invalid="ignore"):
            step = dg[todo] - val / der
        inside = np.isfinite(step) & (step > lo_t) & (step < up_t)
        new = np.where(inside, step, np.where(np.isfinite(up_t), 0.5 * (lo_t + up_t), 2 * lo_t))
        dg[todo] = np.where(done, dg[todo], new)
        todo = todo[~done]
    val, _, phi = h(dg, xt, target)
    worst = float(np.max(np.abs(val) * phi))
    raise ConvergenceError(
        f"the J2 return mapping did not converge in {MAX_ITERATIONS} iterations "
        f"(relative residual {worst:.3g} of the yield surface's size)",
        iterations=MAX_ITERATIONS,
        residual=worst,
    )


def update(law: J2Law, strain: F, state: J2State) -> J2Response:
    """The backward-Euler step of material points to total ``strain`` ``S + (3,)``
    from ``state``: stresses, consistent tangents, incremental energies and the
    new state.

    Raises:
        ConvergenceError: the return mapping failed (its residual named).
    """
    eps = np.asarray(strain, dtype=float)
    shape = eps.shape[:-1]
    eps = eps.reshape(-1, 3)
    ep = state.plastic_strain.reshape(-1, 3)
    beta = state.back_stress.reshape(-1, 3)
    alpha = state.equivalent.reshape(-1)
    c = elastic_matrix(law)
    sigma = (eps - ep) @ c  # the trial (C symmetric)
    xi_t = sigma - beta
    phi2 = np.sum((xi_t @ P) * xi_t, axis=1)
    kappa = law.yield_stress + law.hardening_iso * alpha
    trial = 0.5 * phi2 - kappa**2 / 3.0
    flows = trial > TOLERANCE * kappa**2
    tangent = np.broadcast_to(c, (len(eps), 3, 3)).copy()
    ep_new, beta_new, alpha_new = ep.copy(), beta.copy(), alpha.copy()
    if np.any(flows):
        k = np.flatnonzero(flows)
        xt = xi_t[k] @ _Q  # the trial in P's frame
        dg = _gamma(law, xt, alpha[k])
        a = 2.0 / 3.0 * law.hardening_kin + law.c_eigen * _P_EIGEN
        xi = (xt / (1.0 + dg[:, None] * a)) @ _Q.T
        pxi = xi @ P
        phi = np.sqrt(np.einsum("ki,ki->k", xi, pxi))
        ep_new[k] = ep[k] + dg[:, None] * pxi
        beta_new[k] = beta[k] + (2.0 / 3.0 * law.hardening_kin) * dg[:, None] * xi
        alpha_new[k] = alpha[k] + math.sqrt(2.0 / 3.0) * dg * phi
        sigma[k] = xi + beta_new[k]
        tangent[k] = _consistent_tangent(law, xi, pxi, phi, dg)
    d = eps - ep_new
    energy = 0.5 * np.sum((d @ c) * d, axis=1) + _kinematic_energy(law, ep_new)
    energy += law.hardening_iso * alpha_new**2 / 2.0
    energy[flows] += law.yield_stress * (alpha_new[flows] - alpha[flows])  # the dissipation
    new = J2State(ep_new.reshape(shape + (3,)), beta_new.reshape(shape + (3,)),
                  alpha_new.reshape(shape))  # fmt: skip
    return J2Response(
        sigma.reshape(shape + (3,)),
        tangent.reshape(shape + (3, 3)),
        energy.reshape(shape),
        new,
        flows.reshape(shape),
    )


def _consistent_tangent(law: J2Law, xi: F, pxi: F, phi: F, dg: F) -> F:
    """(k, 3, 3) d sigma / d eps of flowing points, by implicit differentiation
    of the projection's equations in ``(xi, dgamma)``::

        theta xi + dgamma C P xi - xi_trial(eps) = 0,   theta = 1 + 2/3 H_kin dgamma
        phi(xi) - sqrt(2/3) kappa(alpha_n + sqrt(2/3) dgamma phi(xi)) = 0

    and ``sigma = theta xi + beta_n``. The linear system ``[[A, b], [r^T, d]]
    (dxi, ddgamma) = (C, 0) deps`` is solved in closed form: ``A = theta I +
    dgamma C P = Q diag(l) Q^T`` in the frame ``Q`` where ``C`` and ``P`` are
    diagonal, so ``ddgamma = -r^T A^-1 C / (d - r^T A^-1 b)`` and ``dxi =
    A^-1 C - A^-1 b ddgamma``.
    """
    hk, hi = law.hardening_kin, law.hardening_iso
    r23 = math.sqrt(2.0 / 3.0)
    theta = 1.0 + 2.0 / 3.0 * hk * dg
    c_eig = law.c_eigen
    lam = theta[:, None] + dg[:, None] * (c_eig * _P_EIGEN)  # A's eigenvalues (k, 3)
    b = 2.0 / 3.0 * hk * xi + pxi @ elastic_matrix(law)  # d/ddgamma of the first equations
    r = pxi / phi[:, None] * (1.0 - r23 * hi * r23 * dg)[:, None]  # dphi/dxi (1 - ...)
    d = -r23 * hi * r23 * phi
    rq = r @ _Q
    a_inv_b = ((b @ _Q) / lam) @ _Q.T
    ca = c_eig / lam  # A^-1 C's eigenvalues
    row = (rq * ca) @ _Q.T  # r^T A^-1 C (k, 3)
    ds = -row / (d - np.sum(r * a_inv_b, axis=1))[:, None]  # d dgamma / d eps
    dxi = (_Q * ca[:, None, :]) @ _Q.T - a_inv_b[:, :, None] * ds[:, None, :]
    return theta[:, None, None] * dxi + 2.0 / 3.0 * hk * xi[:, :, None] * ds[:, None, :]
