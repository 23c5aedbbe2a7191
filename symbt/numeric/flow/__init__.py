"""What the map preserves and interpolates: the invariants ``H_k`` and ``tr L(lam)``, the real
Φ, the flow coefficients ``c_k`` and the Hamiltonian field of ``G = sum_k c_k H_k``.
"""
