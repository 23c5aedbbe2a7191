"""Symbolic layer (SymPy): the Toda model, Darboux matrices, generating function."""
from .toda import TodaModel, toda_model, local_lax

__all__ = ["TodaModel", "toda_model", "local_lax"]
