"""The shape of a report part, the record of computed parts, and the compute step.

A :class:`Part` is what one module of the report contributes: a frozen record it
computes from the design and from the records of the parts it ``needs``, one
:class:`~hexaleg.output.report.document.Section` of text, tables and figures made
from the records, the files it writes (figures, CSV), and its keys in ``report.json``.
:func:`compute_parts` runs every part once, each after the parts it needs, into a
frozen :class:`ReportData`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Generic, TypeVar

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.output.report.options import ReportOptions
from hexaleg.robot.model import HexapodModel
from hexaleg.study.progress import Progress

if TYPE_CHECKING:
    from hexaleg.output.report.document import Section

R = TypeVar("R")


@dataclass(frozen=True)
class ReportData:
    """The design, the options, its model, and every part's record, computed once.

    Attributes:
        design: The analysed design.
        options: The sweep sizes and choices used.
        model: The design's Pinocchio model (its URDF is ``model.urdf``).
        records: Each part's record, keyed by the record's type; read with ``data[Type]``.

    """

    design: HexapodDesign
    options: ReportOptions
    model: HexapodModel
    records: Mapping[type, Any] = field(default_factory=dict)

    def __getitem__(self, kind: type[R]) -> R:
        """The record of type ``kind``; fails if no part computed it (yet)."""
        try:
            record: R = self.records[kind]
        except KeyError:
            raise HexalegError(
                f"report part record {kind.__name__} is not computed: list the part that "
                "makes it in the needs of the part that reads it"
            ) from None
        return record

    def with_record(self, record: object) -> ReportData:
        """A copy holding ``record`` too."""
        records = {**self.records, type(record): record}
        return ReportData(self.design, self.options, self.model, records)

    def only(self, kinds: Sequence[type]) -> ReportData:
        """A copy holding only the records of ``kinds`` (what a part declared it needs)."""
        records: dict[type, Any] = {kind: self[kind] for kind in kinds}
        return ReportData(self.design, self.options, self.model, records)


def _no_files(data: ReportData, out: Path) -> None:
    """A part that writes no file."""


def _no_json(record: Any) -> dict[str, Any]:
    """A part with no key in ``report.json``."""
    return {}


@dataclass(frozen=True)
class Part(Generic[R]):
    """One part of the report (see the package docstring for how to add one).

    Attributes:
        record: The type of the frozen record :attr:`compute` returns.
        compute: The record, from the design, options, model and the needed records.
        section: The part's section of the report, from every record (pure).
        needs: Record types of the parts whose records :attr:`compute` reads.
        step: What the progress bar says while computing it.
        files: Writes the part's figures and tables into the report folder.
        json: The part's top-level keys of ``report.json`` (SI units, radians).

    """

    record: type[R]
    compute: Callable[[ReportData], R]
    section: Callable[[ReportData], Section]
    needs: tuple[type, ...] = ()
    step: str = ""
    files: Callable[[ReportData, Path], None] = _no_files
    json: Callable[[R], dict[str, Any]] = _no_json


def compute_order(parts: Sequence[Part[Any]]) -> list[Part[Any]]:
    """``parts`` ordered so that each comes after the parts it needs (stable otherwise)."""
    by_record = {part.record: part for part in parts}
    ordered: list[Part[Any]] = []
    visiting: set[type] = set()

    def visit(part: Part[Any]) -> None:
        if part in ordered:
            return
        if part.record in visiting:
            raise HexalegError(f"report parts need each other in a circle at {part.record}")
        visiting.add(part.record)
        for kind in part.needs:
            if kind not in by_record:
                raise HexalegError(f"no report part makes {kind.__name__}")
            visit(by_record[kind])
        visiting.discard(part.record)
        ordered.append(part)

    for part in parts:
        visit(part)
    return ordered


def compute_parts(
    design: HexapodDesign, options: ReportOptions, parts: Sequence[Part[Any]]
) -> ReportData:
    """Every part's record, each computed from only what it needs.

    Progress is shown as a study's (:class:`~hexaleg.study.progress.Progress`): a bar on a
    terminal, a line every few seconds elsewhere, naming the step that runs.
    """
    ordered = compute_order(parts)
    with Progress(len(ordered) + 1, unit="steps", show=options.progress) as shown:
        shown.update(0, "model and URDF")
        data = ReportData(design, options, HexapodModel(design))
        for part in ordered:
            shown.update(1, part.step or part.record.__name__)
            data = data.with_record(part.compute(data.only(part.needs)))
        shown.update(1)
    return data
