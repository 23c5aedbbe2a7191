
import pytest


@pytest.fixture(autouse=True)
def _isolated_cache(tmp_path_factory, monkeypatch):
    """Every test gets its own claim cache, so results never leak between tests or from a user's cache."""
    monkeypatch.setenv("SYMBT_CACHE_DIR", str(tmp_path_factory.mktemp("symbt-cache")))
    yield
