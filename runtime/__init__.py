"""Hand-written runtime around the generated kernels (NumPy only, no SymPy).

``generated/`` holds what symbolic/ emits: scalar coefficient kernels valid for every n and
component kernels for n = 3, 4. This package applies the coefficient kernels to batches of
n x n matrices (general n, einsum/broadcast) and dispatches to the component kernels where they
are faster. It is the layer ``simulate/`` calls; it never builds a formula of its own beyond the
definitions it names (eq:M-O, eq:motion-general), and the assembly it does is tested against
mpmath in tests/test_kernels_*.py.
"""

from chaplygin_nd.runtime.axisym import (
    L_gamma,
    angular_velocity,
    chi,
    energy,
    expm_skew,
    unvec,
    vec,
    vector_field,
    vertical_solution,
    zeta,
)

__all__ = ["L_gamma", "angular_velocity", "vector_field", "energy", "zeta", "chi",
           "vertical_solution", "expm_skew", "vec", "unvec"]
