"""``python -m symbt.benchmarks.numeric_timings``: the report degrades to what is installed (no traceback
without an extra)."""
import subprocess
import sys

import pytest

from symbt.numeric.multiprec.runners import flint_available

_BLOCKED = """
import sys
for name in ("flint", "heyoka", "numba"):
    sys.modules[name] = None          # as on a core install: importing them raises ImportError
from symbt.benchmarks.numeric_timings import main
main(["--quick"])
"""


def test_report_runs_on_a_core_install():
    r = subprocess.run([sys.executable, "-c", _BLOCKED], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    out = r.stdout
    assert "[no numba: plain-Python kernel]" in out
    assert out.count("[no python-flint: no Arb path]") == 2 and 'pip install "symbt[peers]"' in out
    assert 'certified orbits: skipped (python-flint is not installed: pip install "symbt[certified]")' in out
    assert "nan ms" not in out and "xnan" not in out          # what the report printed before it crashed


@pytest.mark.skipif(not flint_available(), reason="needs python-flint (pip install 'symbt[certified]')")
def test_certified_radius_grows_with_the_steps():
    from symbt.benchmarks.numeric_timings import certified_growth

    rows = certified_growth(prec=200, steps=(1, 5, 10, 20))
    assert [n for n, _ in rows] == [1, 5, 10, 20]
    radii = [r for _, r in rows]
    assert all(0 < a < b for a, b in zip(radii, radii[1:])), radii     # the wrapping effect: strictly growing
    assert radii[0] < 2.0 ** -150                                       # one step loses few of the 200 bits
