"""Simulate the sheet as steel and read its stresses.

    python examples/simulate_stress.py

Forms the flat sheet into the design, releases it, stands it on the ground
under its weight (``onefold simulate``'s stages), on the coarse mesh of a
preview, and prints where it yields and the largest stress standing.
"""

import numpy as np

import onefold_cad as of

design = of.load_template("patkau-one-fold")  # 304 stainless: E, nu, yield stress
sim = of.simulate(design, mesh="coarse")  # a preview; mesh="normal" for the numbers

print(f"mesh: {sim.nodes} nodes, {sim.triangles} triangles, yield {sim.yield_stress_MPa} MPa")
if sim.formed is not None:
    print(f"formed: {sim.formed.plastic_area_share:.1%} of the sheet yields")
print(f"stands: {sim.standing.stands}")
if sim.face_stress_MPa is not None:
    stress = np.asarray(sim.face_stress_MPa)
    worst = int(np.argmax(stress))
    print(f"largest stress standing: {stress[worst]:.3g} MPa (face {worst})")
for line in sim.warnings:
    print("warning:", line)
