"""Newton's method on an energy with a sparse Hessian: line search, regularisation,
fixed unknowns eliminated.

Each step solves ``(H_ff + lambda diag|H_ff|) p = -g_f`` by a sparse LDL^T
factorisation without pivoting (QDLDL, :class:`SymmetricFactor`: one
symbolic analysis, AMD-ordered, for every matrix of the Hessian's structure,
so each Newton step refactors numerically only; ``D``'s signs are the
matrix's inertia): ``lambda = 0`` first, then growing shifts while the
factorisation fails, the matrix is not positive definite or the step is no
descent direction. Full steps
are taken under a watchdog: when a few of them have not brought the energy
sufficiently (Armijo) below the last reference point, the method returns there
and backtracks along its direction. Convergence: the
largest residual component, directors' moments divided by a length, at most
``max(rtol * force_scale, atol)``.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import qdldl
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from onefold_cad.errors import ConvergenceError

__all__ = ["FactorReuse", "NewtonResult", "Progress", "SymmetricFactor", "minimize", "restrict"]

F = NDArray[np.float64]
#: ``fun(q, order) -> (energy, gradient, hessian)``, gradient and Hessian None below
#: orders 1 and 2; the Hessian's structure must not change between calls.
EnergyFunction = Callable[[F, int], tuple[float, F | None, sp.csc_matrix | None]]
Progress = Callable[[int, float, float], None]

_SHIFTS = (0.0, 1e-8, 1e-6, 1e-4, 1e-3, 1e-2, 0.03, 0.1, 0.3, 1.0, 3.0, 10.0, 100.0, 1e3)


@dataclass(frozen=True)
class NewtonResult:
    """A converged minimiser.

    Attributes:
        q: (N,) the state.
        energy: its energy (J).
        gradient: (N,) the full gradient there (at fixed DOFs: the reactions).
        residual: the final scaled residual (N).
        tolerance: the residual it had to reach (N).
        iterations: Newton steps taken.
    """

    q: F
    energy: float
    gradient: F
    residual: float
    tolerance: float
    iterations: int


def restrict(h: sp.csc_matrix, free: NDArray[np.bool_]) -> tuple[NDArray[np.int64], Callable]:
    """A fast restriction of matrices with ``h``'s structure to the free rows and columns.

    Returns the kept data positions and a function mapping a matrix with the same
    structure to its free-free block.
    """
    cols = np.repeat(np.arange(h.shape[1]), np.diff(h.indptr))
    keep = np.flatnonzero(free[h.indices] & free[cols])
    renumber = np.cumsum(free) - 1
    r = int(free.sum())
    indices = renumber[h.indices[keep]]
    indptr = np.searchsorted(renumber[cols[keep]], np.arange(r + 1)).astype(np.int64)

    def block(full: sp.csc_matrix) -> sp.csc_matrix:
        return sp.csc_matrix((full.data[keep], indices, indptr), shape=(r, r))

    return keep, block


class SymmetricFactor:
    """``LDL^T`` factorisations of symmetric matrices of one sparsity structure
    plus a diagonal shift (QDLDL: the ordering and symbolic analysis are done
    once, each :meth:`factor` refactors numerically).

    Args:
        a: (n, n) CSC, symmetric, with every diagonal entry in its structure
            (stored, even if zero).
    """

    def __init__(self, a: sp.csc_matrix) -> None:
        n = a.shape[0]
        cols = np.repeat(np.arange(n), np.diff(a.indptr))
        rows = a.indices
        keep = rows <= cols  # the upper triangle, column by column as stored
        self._keep = np.flatnonzero(keep)
        ptr = np.zeros(n + 1, dtype=np.int64)
        np.cumsum(np.bincount(cols[keep], minlength=n), out=ptr[1:])
        diag = np.flatnonzero(rows[keep] == cols[keep])
        if len(diag) != n:
            raise ValueError("the matrix's structure lacks diagonal entries")
        self._diag = diag
        # The upper triangle's matrix, built once: each factor refills its data
        # (QDLDL reads only the values on an update).
        self._upper = sp.csc_matrix((np.zeros(len(self._keep)), rows[keep], ptr), shape=(n, n))
        self._solver: qdldl.Solver | None = None

    def factor(self, a: sp.csc_matrix, shift: F | None = None) -> bool:
        """Factor ``a + diag(shift)`` (``a`` of this structure); whether it is
        positive definite (every pivot of ``D`` positive and finite). A
        factorisation that breaks down counts as not definite."""
        upper = self._upper
        np.take(a.data, self._keep, out=upper.data)
        if shift is not None:
            upper.data[self._diag] += shift
        try:
            if self._solver is None:
                self._solver = qdldl.Solver(upper, upper=True)
            else:
                self._solver.update(upper, upper=True)
            # D's signs: qdldl gives D only with L (``factors``); no call reads D alone.
            d = self._solver.factors()[1]
        except (ValueError, RuntimeError):
            self._solver = None
            return False
        return bool(np.all(d > 0) and np.all(np.isfinite(d)))

    def solve(self, b: F) -> F:
        """``x`` with ``(a + diag(shift)) x = b`` of the last :meth:`factor`."""
        assert self._solver is not None
        return np.asarray(self._solver.solve(b), dtype=float)


class FactorReuse:
    """The :class:`SymmetricFactor` of each sparsity structure a run of solves
    meets (a load path's steps, a contact iteration's passes), so a structure
    seen before is refactored numerically only: QDLDL's ordering and symbolic
    analysis (about as long as a factorisation again) are done once per
    structure. Holds at most ``size`` structures, the most recent; not shared
    between threads (a factor holds its last factorisation).
    """

    def __init__(self, size: int = 4) -> None:
        self._size = size
        self._kept: list[tuple[NDArray[np.int32], NDArray[np.int32], SymmetricFactor]] = []

    def factor_for(self, a: sp.csc_matrix) -> SymmetricFactor:
        """A factor for matrices of ``a``'s structure: the one kept for it, or a new one."""
        for i, (indptr, indices, factor) in enumerate(self._kept):
            if np.array_equal(indptr, a.indptr) and np.array_equal(indices, a.indices):
                self._kept.append(self._kept.pop(i))
                return factor
        factor = SymmetricFactor(a)
        self._kept.append((a.indptr.copy(), a.indices.copy(), factor))
        del self._kept[: -self._size]
        return factor


def minimize(
    fun: EnergyFunction,
    q0: ArrayLike,
    fixed: NDArray[np.bool_],
    *,
    residual_scale: F | None = None,
    force_scale: float = 0.0,
    rtol: float = 1e-9,
    atol: float = 0.0,
    max_iter: int = 60,
    watchdog: int = 6,
    start_scales: bool = True,
    callback: Progress | None = None,
    reuse: FactorReuse | None = None,
) -> NewtonResult:
    """Minimise ``fun`` over the free unknowns, starting from ``q0``.

    Args:
        fun: the energy with gradient and sparse (CSC, fixed structure) Hessian.
        q0: (N,) start; fixed entries keep their values.
        fixed: (N,) bool, unknowns held at their start values.
        residual_scale: (N,) factors turning gradient entries into forces (1 for
            coordinates, 1 / length for angles); default all 1.
        force_scale: the load scale (N); the tolerance is ``rtol`` times the
            larger of it and the start's residual, floored at ``atol``.
        max_iter: Newton steps allowed.
        watchdog: full Newton steps allowed without a sufficient decrease of the
            energy below the last reference point before going back to it for a
            line search (the watchdog technique: thin shells' stiff membranes make
            a monotone search crawl at steps of about a thickness).
        start_scales: whether a start's residual above ``force_scale`` raises the
            tolerance (False for a start predicted along a load path: its
            residual measures the prediction's error, not the load).
        callback: ``callback(iteration, residual, energy)`` before every step.
        reuse: the factors of earlier solves, to refactor a structure they met
            numerically only (None: a new factor, analysed anew).

    Raises:
        ConvergenceError: no convergence in ``max_iter`` steps, or no step that
            lowers the energy could be found.
    """
    q = np.array(q0, dtype=float)
    free = ~np.asarray(fixed, dtype=bool)
    scale = np.ones(len(q)) if residual_scale is None else np.asarray(residual_scale, float)
    if not free.any():  # an imposed state: nothing to solve, no Hessian needed
        energy, grad, _ = fun(q, 1)
        assert grad is not None
        if callback is not None:
            callback(0, 0.0, energy)
        return NewtonResult(q, energy, grad, 0.0, max(rtol * force_scale, atol), 0)
    energy, grad, hess = fun(q, 2)
    assert grad is not None and hess is not None
    _, block = restrict(hess, free)
    first = block(hess)
    factors = SymmetricFactor(first) if reuse is None else reuse.factor_for(first)

    def residual(g: F) -> float:
        return float(np.max(np.abs(g[free] * scale[free]), initial=0.0))

    res = residual(grad)
    tol = max(rtol * (max(force_scale, res) if start_scales else force_scale), atol)
    shift_start, relaxed = 0, 0
    before = (math.inf, math.inf)  # residual and energy before the last full step
    ref: tuple[F, float, F, sp.csc_matrix, float] | None = None
    for it in range(max_iter + 1):
        if callback is not None:
            callback(it, res, energy)
        if not math.isfinite(res):
            break
        if res <= tol:
            return NewtonResult(q, energy, grad, res, tol, it)
        if it == max_iter:
            break
        # Full steps may climb once (a thin shell's rotation stretches it for a step);
        # a later one that raises both the energy and the residual ends them.
        worse = relaxed >= 2 and res > before[0] and energy > before[1]
        monotone = relaxed >= watchdog or worse
        if monotone and ref is not None:
            # The full steps since the reference did not lower the energy enough:
            # back to it, and search along a line there.
            q, energy, grad, hess = ref[0].copy(), ref[1], ref[2], ref[3]
        taken = False
        ahead: tuple[F, sp.csc_matrix] | None = None  # the gradient and Hessian at the new q
        for p, slope, k in _directions(factors, block(hess), grad[free], shift_start):
            if monotone:
                accepted = _line_search(fun, q, free, p, energy, slope)
                if accepted is None:
                    continue
                q, energy = accepted
                relaxed = 0
            else:
                if relaxed == 0:
                    ref = (q.copy(), energy, grad, hess, slope)
                before = (res, energy)
                trial = q.copy()
                trial[free] += p
                # a full step is kept but for a non-finite energy: evaluate it whole
                e, g_trial, h_trial = fun(trial, 2)
                if not math.isfinite(e):
                    continue
                assert g_trial is not None and h_trial is not None
                ahead = (g_trial, h_trial)
                assert ref is not None
                slack = 1e-13 * max(abs(ref[1]), 1e-300)
                relaxed = 0 if e <= ref[1] + 1e-4 * ref[4] + slack else relaxed + 1
                q, energy = trial, e
            shift_start = max(k - 1, 0)
            taken = True
            break
        if not taken:
            raise ConvergenceError(
                f"Newton found no descent step at iteration {it}: residual {res:.3g} N "
                f"(tolerance {tol:.3g} N)",
                iterations=it,
                residual=res,
            )
        if ahead is not None:
            grad, hess = ahead
        else:
            energy, grad, hess = fun(q, 2)
            assert grad is not None and hess is not None
        res = residual(grad)
    raise ConvergenceError(
        f"Newton did not converge in {max_iter} iterations: residual {res:.3g} N "
        f"(tolerance {tol:.3g} N)",
        iterations=max_iter,
        residual=res,
    )


def _directions(factors: SymmetricFactor, hf: sp.csc_matrix, gf: F, shift_start: int):
    """Newton directions ``p`` with ``slope = g.p < 0`` from ``(H + lambda diag|H|) p = -g``
    for growing shifts ``lambda`` (only positive definite matrices are used).
    Yields ``(p, slope, k)``, ``k`` the shift's index (0: unshifted)."""
    diag = np.abs(hf.diagonal())
    diag = np.where(diag > 0, diag, max(float(diag.max(initial=0.0)), 1.0))
    for k in range(shift_start, len(_SHIFTS)):
        lam = _SHIFTS[k]
        if not factors.factor(hf, None if lam == 0 else lam * diag):
            continue
        p = -factors.solve(gf)
        slope = float(gf @ p)
        if slope < 0 and np.all(np.isfinite(p)):
            yield p, slope, k


def _line_search(
    fun: EnergyFunction, q: F, free: NDArray[np.bool_], p: F, energy: float, slope: float
) -> tuple[F, float] | None:
    """Backtracking Armijo search along ``p`` (free entries); None if it fails."""
    alpha = 1.0
    slack = 1e-13 * max(abs(energy), 1e-300)
    trial = q.copy()
    for _ in range(40):
        trial[free] = q[free] + alpha * p
        e = fun(trial, 0)[0]
        if math.isfinite(e) and e <= energy + 1e-4 * alpha * slope + slack:
            return trial, e
        alpha *= 0.5
    return None
