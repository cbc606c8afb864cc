r"""Mutation testing: does a check notice when a formula is wrong?

A mutant is one one-token change of one function (:mod:`.operators`), applied in memory by
replacing the function's ``__code__`` (no source file is written). Two commands use it:

* ``chaplygin mutate`` (:mod:`.printed`, ``make mutate``) — the transcriptions of
  ``symbolic/printed/`` against the ledger rows that reach them;
* ``chaplygin mutate-derivations`` (:mod:`.command`, ``make mutate-derivations``) — the
  derivations of ``symbolic/`` (:mod:`.derivations`) and the runtime (:mod:`.runtime`).

What belongs here, by module: the operators (:mod:`.operators`); running a row with a mutant and
its time budget (:mod:`.checks`); deciding that a mutant no row told apart is equivalent
(:mod:`.equivalence`, and the reviewed arguments of :mod:`.argued`); recording a function's calls
once and replaying them on each mutant (:mod:`.replay`), every function's calls in one run of
each row at planning (:mod:`.planned`); running a row or a test session
with a mutant from a process parked at the function's first call (:mod:`.forkpoint`); keeping caches that a mutant cannot
reach (:mod:`.cache_scope`); the workers, grouping and progress of a long run
(:mod:`.runloop`); the record file, ``--resume`` and its consistency (:mod:`.record`); the
command-line checks both commands share (:mod:`.options`). Which rows reach which function is the
ledger's map (:mod:`chaplygin_nd.ledger.reach`), not part of this package.
"""
