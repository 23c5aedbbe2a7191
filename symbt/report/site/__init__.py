"""``symbt report --html DIR``: the paper, annotated -- a static site built from a verify run's JSON.

Offline from the file system (no CDN, no server, no script): a summary page with the paper's
labelled displays in reading order, each rendered as MathML from its ``.tex`` source
(:mod:`.mathml`) with its status badge, evidence and claims; a page per label with its claims
(statement, printed vs corrected, counterexample, residual, cell grid, scope, method, time,
``n_scope``) and its dependency subgraph; the whole dependency graph (:mod:`.graph`); statuses
propagated along the graph (:mod:`.model`: a verified label that uses an erratum is "verified,
depends on ...").  No claim is re-run.

>>> import tempfile
>>> doc = {"claims": [{"id": "c1", "equation": "E", "status": "erratum", "statement": "x < 1", "uses": []}]}
>>> class Lab: label, section, kind, source, refs = "E", "1", "equation", r"\\frac{a}{b}", ()
>>> out = build_site(doc, [Lab()], tempfile.mkdtemp())
>>> out["mathml"], out["statuses"]
({'E': True}, {'E': 'erratum'})
"""
from __future__ import annotations

from .build import build_site
from .graph import graph_svg
from .mathml import macros_of, to_mathml
from .model import Site

__all__ = ["build_site", "Site", "graph_svg", "macros_of", "to_mathml"]
