"""What every backend shares: arithmetic contexts, typed errors, input validation, the scaled
Lax monodromy and the step written once against a context (:func:`~symbt.numeric.core.step.step_core`).

Nothing here imports another sub-package of :mod:`symbt.numeric`.
"""
