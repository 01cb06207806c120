"""Stage 7, the ``exudyn-turnout`` command: one module per command; the entry point is
:func:`exudyn_turnout.cli.main.main` (also ``python -m exudyn_turnout``)."""

__all__: list[str] = []
