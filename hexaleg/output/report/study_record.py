"""The design study's record: what the parts after the study read of it.

The study part (:mod:`.study`) computes it; the recommendation, the statics, the Pareto
front, the walking section and the marks on every study figure (:mod:`.marks`) read it.
"""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd

from hexaleg.study.rows import StudyRow
from hexaleg.study.sweep import StudySpec


@dataclass(frozen=True)
class StudyRecord:
    """The FB sweep (Fig 14–15) on the design's body and posture.

    Attributes:
        spec: What was swept.
        table: One row per design: ranges, FB, torques, payload capacity, errors.
        yours: Your design measured as the study measures its own (it is marked on the
            study's figures).

    """

    spec: StudySpec
    table: pd.DataFrame
    yours: StudyRow
