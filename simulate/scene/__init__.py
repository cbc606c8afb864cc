r"""The scene product: a scene file (:mod:`.spec`), the model planner and its cost model
(:mod:`.planner`, :mod:`.cost`, :mod:`.budget`, :mod:`.accuracy`), the run (:mod:`.run`), outputs
and figures (:mod:`.outputs`, :mod:`.figures`), output folders (:mod:`.outdir`), the cross-check
(:mod:`.crosscheck`), the frequency-map and tori scenes (:mod:`.frequency_map`, :mod:`.tori`) and
the ``chaplygin simulate`` command (:mod:`.cli`). Nothing outside this package imports it but the
project's command line and notebook API."""
