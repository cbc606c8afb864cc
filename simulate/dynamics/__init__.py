r"""The model the simulator integrates: so(n) algebra and the SO(n) invariants (:mod:`.so`), the
vector fields on $P$ and on the reduced space (:mod:`.field`), initial-condition families
(:mod:`.families`), closed forms of the paper's special motions (:mod:`.closed_forms`) and the
physical ball (:mod:`.ball`). Depends only on :mod:`simulate.kernels`."""
