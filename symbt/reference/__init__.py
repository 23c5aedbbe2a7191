"""Independent high-precision routes (mpmath, sympy-free): what the claims compare against.

* :mod:`.literal`   -- the paper's explicit Bäcklund map, computed word for word (Section 3),
  and :func:`reference_step`, the same with automatic guard digits;
* :mod:`.trace`     -- tr L(lambda) as an explicit polynomial (closed walks), the H_k;
* :mod:`.spectral`  -- the real Phi, its gradient, the flow coefficients c_k (eq. ``eqdisc``);
* :mod:`.taylor`    -- Hamiltonian flows by an adaptive Taylor-series method (Theorems 1, 2);
* :mod:`.inverse`   -- the inverse problem c -> (lam0, mu, branch);
* :mod:`.elliptic`  -- N = 2 action-angle variables, the Abel map, the addition formula;
* :mod:`.samples`   -- seeded admissible sample states and the paper's example.

None of these uses :mod:`symbt.numeric`'s stable formulation of the step: they are the
independent side of every comparison.
"""
from __future__ import annotations

from .literal import lax_matrix, literal_step, phi_from_traces, reference_step, spectral_trace_mp
from .samples import admissible_states, paper_state

__all__ = ["lax_matrix", "literal_step", "phi_from_traces", "reference_step", "spectral_trace_mp",
           "admissible_states", "paper_state"]
