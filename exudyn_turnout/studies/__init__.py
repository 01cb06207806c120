"""Studies: many passages from one study file, on one core, a process pool or a cluster.

:mod:`.study` reads a study file (base scenario, factors: full factorial, paired lists,
Latin hypercube, irregularity seeds) and expands it into cases; :mod:`.run` runs them
through a :class:`concurrent.futures.Executor` and writes the results table;
:mod:`.toml_writer` writes the cases' modified turnout and vehicle files.
"""

from exudyn_turnout.studies.run import StudyResult, load_results, run_case, run_study
from exudyn_turnout.studies.study import Case, Study, StudyError, load_study

__all__ = [
    "Case",
    "Study",
    "StudyError",
    "StudyResult",
    "load_results",
    "load_study",
    "run_case",
    "run_study",
]
