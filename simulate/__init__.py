r"""Simulation of the axisymmetric $n$-dimensional Chaplygin sphere with the cheapest exact model.

Four subpackages and one binding, arrows one way (scene → analysis → integrators → dynamics →
kernels → :mod:`generated`):

* :mod:`~simulate.kernels` — the one binding to the verified kernels of :mod:`generated`.
* :mod:`~simulate.dynamics` — the model: so(n) algebra and the SO(n) invariants, vector fields,
  initial-condition families, closed forms (relative equilibria, horizontal motion), the ball.
* :mod:`~simulate.integrators` — DOP853, RKMK4 Lie-group, Taylor reference, heyoka; why a run stops.
* :mod:`~simulate.analysis` — the dynamics analysis that the evidence rows of :mod:`proofs` and
  the frequency maps share: NAFF, chaos indicators, drawn ensembles, controls, the result cache,
  frequency maps, Poincaré sections.
* :mod:`~simulate.scene` — the scene product: scene files, planner and cost model, run, outputs
  and figures, output folders, cross-check, the ``chaplygin simulate`` command.

Imports no SymPy.
"""
