"""``onefold sweep``: many designs of one template, evaluated on a process
pool or a Dask cluster, written as a table, Design Explorer's data.csv, a
Pareto front and a picture (docs/sweep.md).

The modules, each one job: :mod:`.spec` reads ``--vary NAME=SPEC``,
:mod:`.samplers` makes the design points (grid, Latin hypercube, Sobol'),
:mod:`.plan` checks the whole sweep before any design runs, :mod:`.measures`
is the registry of what each design gets, :mod:`.evaluate` is the workers'
task, :mod:`.backends` runs the tasks (this process, a pool, Dask),
:mod:`.journal` keeps every finished row, :mod:`.runner` drives a run,
:mod:`.pareto` finds the non-dominated designs, :mod:`.tables` and
:mod:`.outputs` write the files, :mod:`.progress` reports on stderr.
Heavy libraries are imported where they are used: scipy by the samplers,
pyarrow by the tables, dask by the backends, matplotlib by the export
adapters.
"""
