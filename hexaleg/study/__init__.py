"""Design studies: many designs on any executor (:mod:`.sweep`), sensitivity, recommendation.

A lazy front door (:mod:`hexaleg._lazy`): a name's module is imported on first use, so
a command that only needs a study's limits does not load pandas, the analyses or pymoo.
The sweep over an executor is ``hexaleg.study.sweep.sweep`` (its module's name: the
package cannot offer both lazily).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from hexaleg._lazy import lazy_exports

__all__ = [
    "Recommendation",
    "StudySpec",
    "best_posture",
    "dask_executor",
    "local_pool",
    "peak_table",
    "recommend",
    "relative_variants",
    "run_study",
    "sensitivity_table",
    "sweep_in_process",
]

__getattr__, __dir__ = lazy_exports(__name__)

if TYPE_CHECKING:  # where each name is from: read by type checkers, the docs and lazy_exports
    from hexaleg.study.executors import dask_executor, local_pool
    from hexaleg.study.posture import best_posture
    from hexaleg.study.recommendation import Recommendation, recommend
    from hexaleg.study.sensitivity import relative_variants, sensitivity_table
    from hexaleg.study.sweep import StudySpec, peak_table, run_study, sweep_in_process
