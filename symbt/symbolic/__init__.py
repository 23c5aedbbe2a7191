"""Symbolic layer (SymPy): the Toda model, Darboux matrices, generating function."""
from .toda import TodaModel, local_lax, toda_model

__all__ = ["TodaModel", "toda_model", "local_lax"]
