"""Tests of ``experiments``, one folder per package. The helpers shared across folders
(``cli_process``, ``sweep_fixtures``) live here: pytest puts this folder on ``sys.path``
because it holds this conftest, so ``from sweep_fixtures import TINY`` works from any of them."""
