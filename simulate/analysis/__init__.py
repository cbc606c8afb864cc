r"""Dynamics analysis shared by the evidence rows of :mod:`proofs` and the frequency maps: NAFF
(:mod:`.naff`), chaos indicators (:mod:`.chaos`), drawn ensembles and their measurement
(:mod:`.draws`, :mod:`.drawn_evidence`, :mod:`.evidence_rows`), orbit experiments
(:mod:`.evidence`, :mod:`.frequencies`), the non-axisymmetric controls (:mod:`.control`), the
result cache (:mod:`.result_cache`), frequency maps (:mod:`.fma`) and Poincaré sections
(:mod:`.poincare`). Uses :mod:`simulate.integrators` and :mod:`simulate.dynamics`; never the scene
product."""
