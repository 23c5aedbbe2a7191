"""The paper's statements as claims, grouped in scenes.

Importing :func:`load_all` registers every claim module; the registry holds
only metadata until a claim is run, so listing scenes is cheap.  Claim
modules import sympy/mpmath but never scipy or matplotlib at import time.
"""
from __future__ import annotations

import importlib

from .base import REGISTRY, SCENES, Claim, Outcome, claim, scene

__all__ = ["REGISTRY", "SCENES", "Claim", "Outcome", "claim", "scene", "load_all", "import_listed", "CLAIM_MODULES"]

# order = order of the report (follows the paper)
CLAIM_MODULES = (
    "section1",
    "toy",
    "toda_model",
    "conventions",
    "single_bt",
    "single_bt_map",
    "appendix_a",
    "composed_map",
    "generating",
    "generating_map",
    "phi",
    "theorem1",
    "theorem2",
    "captions",
    "elliptic_actions",
    "elliptic_angles",
    "addition",
    "inverse",
    "certified",
    "codegen",
    "shipped_step",
    "shipped_spectral",
    "shipped_emitted",
    "shipped_flow",
    "shipped_qd",
    "shipped_paths",
    "shipped_lohner",
    "shipped_routes",
    "shipped_complex",
    "shipped_condition",
    "shipped_existence",
    "shipped_dask",
    "shipped_members",
    "shipped_sample3",
    "shipped_sample45",
    "shipped_seed6",
    "shipped_seed10",
    "seed11",
    "seed13",
    "seed16",
    "seed18",
    "seed21",
    "seed22",
    "seed23",
    "seed26",
    "contexts",
    "shipped_condition_file",
    "shipped_core",
    "shipped_field",
    "shipped_rules",
    "shipped_radius",
    "shipped_edges",
    "shipped_block_file",
    "checker",
    "checker_mutation",
    "checker_identity",
    "checker_sample3",
    "checker_sample45",
    "checker_seed6",
    "checker_screen",
    "checker_screen_scale",
    "checker_seed10",
    "library",
    "library_reference",
    "library_samples",
    "library_moments",
    "library_sampler",
    "library_ref3",
    "library_ref45",
    "library_elliptic_file",
    "library_codegen",
    "codegen_controls",
    "library_emit3",
    "library_derive_file",
    "library_user_file",
    "emitted_user",
    "emitted_sources",
)


def import_listed(package: str, names: tuple[str, ...]) -> None:
    """Import ``package.name`` for every name (a claims package's ``CLAIM_MODULES``); a missing one is skipped."""
    for name in names:
        try:
            importlib.import_module(f"{package}.{name}")
        except ModuleNotFoundError as exc:
            if exc.name != f"{package}.{name}":
                raise


def load_all() -> dict[str, Claim]:
    """Import every claim module (missing optional modules are ignored)."""
    import_listed(__name__, CLAIM_MODULES)
    return REGISTRY
