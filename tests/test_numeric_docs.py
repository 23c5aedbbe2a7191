"""The runnable examples of docs/numeric.md (doctest on the markdown file)."""

import doctest
import pathlib

import pytest

DOC = pathlib.Path(__file__).resolve().parents[1] / "docs" / "numeric.md"


def test_docs_numeric_examples_run():
    pytest.importorskip("flint")
    pytest.importorskip("dask.array")
    result = doctest.testfile(str(DOC), module_relative=False, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 10 and result.failed == 0, result
