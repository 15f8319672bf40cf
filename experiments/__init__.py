"""What users run: planning, sweeps, benchmarks and reports, and the ``partfeeder`` CLI."""
