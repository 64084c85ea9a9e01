"""The report's parts, in the order the report shows them (one line a part)."""

from __future__ import annotations

from typing import Any

from hexaleg.output.report import (
    decision,
    design,
    flexibility,
    manipulability,
    pareto,
    recommendation,
    sensitivity,
    statics,
    study,
    viewer,
    workspace,
)
from hexaleg.output.report.part import Part

PARTS: tuple[Part[Any], ...] = (
    decision.PART,
    design.PART,
    workspace.PART,
    manipulability.PART,
    flexibility.PART,
    study.PART,
    sensitivity.PART,
    statics.PART,
    viewer.PART,
    recommendation.PART,
    pareto.PART,
)
"""Every part of the report, in reading order; each is computed after the parts it needs."""
