"""The stress suite's marker: ``python -m pytest -m stress`` runs the CI-sized stress run alone."""

from __future__ import annotations


def pytest_configure(config):
    config.addinivalue_line("markers", "stress: the CI-sized run of partfeeder stress (~1 min)")
