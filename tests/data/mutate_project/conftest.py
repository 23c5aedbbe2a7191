"""The files beside this one are a *user's* claims project (copied to a temporary directory by
``tests/test_mutate_user.py``), not test modules: keep ``--doctest-modules`` from importing them here."""
collect_ignore = ["note_model.py", "note_claims.py"]
