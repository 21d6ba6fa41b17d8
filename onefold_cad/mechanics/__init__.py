"""The sheet as steel: a shell model of the flat sheet and its static equilibria.

Plain arrays in, plain arrays out, SI units (m, N, Pa, J). The layer imports
the layers below it (the design, its geometry, the choices and the errors),
never the files' writers or the CLI above it.

- ``mesh``: the triangulation (``mesh_sheet``, ``build_mesh``, ``SheetMesh``);
- ``material``, ``shell``: the material and the model (``ShellMaterial``, ``Shell``);
- ``kinematics/``, ``energy``, ``assembly``: the local geometry (faces, edges,
  directors), the energies with exact gradients and sparse Hessians (``evaluate``);
- ``plastic``: the 1D moment law (elastic-perfectly-plastic bending) and the
  faces' states;
- ``j2/``: J2 plasticity at points, through the thickness, on every face,
  and ``simulate --law j2``'s stages and measures;
- ``newton``, ``equilibrium``, ``predictor``: Newton's method (QDLDL's
  LDL^T), supports, ground contact, continuation and its predicted starts,
  forming and the plastic re-solve;
- ``model``, ``stages``, ``simulate``: a design as a sheet model and
  ``onefold simulate``'s stages with either law; ``standing_measures``,
  ``deviation``, ``stress``, ``reserve``, ``results``: what the stages say;
  ``verdicts``: the warnings, and a reserve check left for later;
- ``loads``: outdoor loads on the standing sheet and what anchors it.
"""

from onefold_cad.mechanics.energy import Evaluation, evaluate, second_fundamental_form
from onefold_cad.mechanics.equilibrium import (
    Equilibrium,
    Ground,
    PathStalled,
    solve_directors,
    solve_equilibrium,
    solve_path,
)
from onefold_cad.mechanics.forming import PlasticResult, form_sheet, solve_plastic
from onefold_cad.mechanics.material import ShellMaterial
from onefold_cad.mechanics.mesh import BOUNDARY, CREASE, INTERIOR, SheetMesh, build_mesh, mesh_sheet
from onefold_cad.mechanics.newton import NewtonResult, minimize
from onefold_cad.mechanics.plastic import PlasticState
from onefold_cad.mechanics.shell import (
    Shell,
    director_angles,
    flat_positions,
    hinge_stiffness,
    pack,
    rigid_dofs,
    unpack,
)

__all__ = [
    "BOUNDARY",
    "CREASE",
    "INTERIOR",
    "Equilibrium",
    "Evaluation",
    "Ground",
    "NewtonResult",
    "PathStalled",
    "PlasticResult",
    "PlasticState",
    "SheetMesh",
    "Shell",
    "ShellMaterial",
    "build_mesh",
    "director_angles",
    "evaluate",
    "flat_positions",
    "form_sheet",
    "hinge_stiffness",
    "mesh_sheet",
    "minimize",
    "pack",
    "rigid_dofs",
    "second_fundamental_form",
    "solve_equilibrium",
    "solve_directors",
    "solve_path",
    "solve_plastic",
    "unpack",
]
