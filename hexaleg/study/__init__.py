"""Design studies: many designs on any executor (:mod:`.sweep`), sensitivity, recommendation."""

from hexaleg.study.executors import dask_executor, local_pool
from hexaleg.study.recommendation import Recommendation, recommend
from hexaleg.study.sensitivity import relative_variants, sensitivity_table
from hexaleg.study.sweep import StudySpec, peak_table, run_study, sweep, sweep_in_process

__all__ = [
    "Recommendation",
    "StudySpec",
    "dask_executor",
    "local_pool",
    "peak_table",
    "recommend",
    "relative_variants",
    "run_study",
    "sensitivity_table",
    "sweep",
    "sweep_in_process",
]
