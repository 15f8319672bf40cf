"""``python -m experiments.cli``: the same as ``partfeeder``."""

from experiments.cli.entry import main

main()
