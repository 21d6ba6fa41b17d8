"""``onefold compensate``: what to fabricate so that the steel stands as designed.

The map:

- :mod:`~onefold_cad.compensate.target`: the target (the designed form, or
  a height and span), checked before any simulation;
- :mod:`~onefold_cad.compensate.evaluate`: one candidate simulated
  (``onefold simulate`` as a black box) and measured against the target;
- :mod:`~onefold_cad.compensate.parallel`: where the simulations run
  (this process, a process pool, a Dask cluster);
- :mod:`~onefold_cad.compensate.optimise`: the least-squares loop, coarse
  mesh then normal;
- :mod:`~onefold_cad.compensate.run`: the whole compensation and its result
  (before and after, the compensated design, the crease angles).
"""
