"""``symbt codegen``: emit the SymPy derivations as numeric code (Python or C), and check it.

* :mod:`.derive` -- the SymPy sources of the emitted functions and their closed forms
  (:mod:`.transport`: the closed form's slopes, built as :mod:`symbt.numeric` computes them);
  :mod:`.kernels` -- the one-site kernels of the transfer-matrix form;
* :mod:`.emit`, :mod:`.emit_loop`, :mod:`.emit_c` -- the Python modules ``toda{N}.py``
  (closed form for N < :data:`LOOP_FROM`, loops over sites from there on) and the C99
  ``toda{N}.c``/``.h``; :mod:`.printer` prints expressions, :mod:`.runtime` and
  :mod:`.loop_template` hold the hand-written parts;
* :mod:`.zullo` -- the closed forms declared with ``symbt.emit`` (typed form) and rendered by the
  user path :mod:`.user` (dogfooding);
* :mod:`.files`, :mod:`.provenance` -- which files, written atomically with a provenance
  header; ``--check`` catches a missing, stale or hand-edited file without SymPy;
* :mod:`.cli`, :mod:`.project` -- the command, acting on the checkout you stand in;
* :mod:`.verify` -- emitted code vs the SymPy source at high precision (scene ``codegen``).

Size and time of the emitted code as N grows: :mod:`symbt.benchmarks.codegen_scaling`.

See docs/codegen.md.

>>> from symbt.codegen import file_names, form_of
>>> file_names((2, 3, 8)), form_of(3), form_of(8)
(['__init__.py', 'toda2.py', 'toda3.py', 'toda8.py'], 'closed', 'transfer-matrix')
"""
from __future__ import annotations

from .cli import main
from .files import DEFAULT_OUT, LANGUAGES, LOOP_FROM, TARGETS, check, file_names, form_of, generate, render
from .forms import Language
from .project import find_project
from .provenance import GENERATOR_VERSION, content_hash, derivation_hash, derivation_sources, read_header

__all__ = ["main", "generate", "check", "render", "file_names", "derivation_hash", "derivation_sources",
           "content_hash", "read_header", "find_project", "form_of", "TARGETS", "LANGUAGES", "LOOP_FROM",
           "GENERATOR_VERSION", "DEFAULT_OUT", "Language"]
