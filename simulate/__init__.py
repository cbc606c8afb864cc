r"""Simulation of the axisymmetric $n$-dimensional Chaplygin sphere with the cheapest exact model.

Modules, one idea each: :mod:`~simulate.scene` (TOML scenes, validation), :mod:`~simulate.families`
(initial conditions), :mod:`~simulate.dispatch` / :mod:`~simulate.generated_adapter` (the binding to
:mod:`generated`), :mod:`~simulate.field` (vector fields), :mod:`~simulate.integrators` (DOP853,
RKMK4 Lie-group, Taylor reference), :mod:`~simulate.closed_forms` (relative equilibria and their
reconstruction), :mod:`~simulate.planner` (model choice), :mod:`~simulate.run` (execution),
:mod:`~simulate.outputs` (arrays, files, plots), :mod:`~simulate.crosscheck`, :mod:`~simulate.cli`.
Imports no SymPy.
"""
