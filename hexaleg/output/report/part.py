"""The shape of a report part, the record of computed parts, and the compute step.

A :class:`Part` is what one module of the report contributes: a frozen record it
computes from the robot and from the records of the parts it ``needs``, one
:class:`~hexaleg.output.report.document.Section` of text, tables and figures made
from the records, the files it writes (figures, CSV), its keys in ``report.json``, and
whether it holds for the robot reported on (:attr:`Part.holds`, asked of the robot's
capabilities: the paper's sweeps hold where every leg is the design's, the sensitivity
table where the body may be varied). :func:`compute_parts` runs every part that holds
once, each after the parts it needs, into a frozen :class:`ReportData`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Generic, Literal, TypeVar

import numpy as np

from hexaleg._version import __version__
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import HexalegError
from hexaleg.output.report.options import ReportOptions
from hexaleg.output.report.section import Section
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.robot import Robot, as_robot, template_robot
from hexaleg.study.progress import Progress

R = TypeVar("R")

Level = Literal[0, 1, 2]
"""A part's heading level: unnumbered, a section, a subsection."""


@dataclass(frozen=True)
class LeftOut:
    """A section of the report that does not hold for the robot reported on, and why.

    Attributes:
        section: The section, in words.
        why: Why it is left out; empty where there is nothing to say (a section of another
            robot's report, or of an option not given).

    """

    section: str = ""
    why: str = ""


@dataclass(frozen=True)
class ReportData:
    """The robot, the options, and every part's record, computed once.

    Attributes:
        design: The analysed design (the robot's).
        options: The sweep sizes and choices used.
        model: The robot's Pinocchio model (its URDF is ``model.urdf``).
        records: Each part's record, keyed by the record's type; read with ``data[Type]``.
        parts: The report's parts, in reading order.
        robot: The robot reported on (hexaleg's template at ``design`` if not given).
        left_out: The sections that do not hold for it, each said once.

    """

    design: HexapodDesign
    options: ReportOptions
    model: HexapodModel
    records: Mapping[type, Any] = field(default_factory=dict)
    parts: tuple[Part[Any], ...] = ()
    robot: Robot = None  # type: ignore[assignment]  # hexaleg's template at design
    left_out: tuple[LeftOut, ...] = ()

    def __post_init__(self) -> None:
        if self.robot is None:
            object.__setattr__(self, "robot", template_robot(self.design))

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
        return replace(self, records={**self.records, type(record): record})

    def only(self, kinds: Sequence[type]) -> ReportData:
        """A copy holding only the records of ``kinds`` (what a part declared it needs)."""
        return replace(self, records={kind: self[kind] for kind in kinds})

    def number(self, kind: type) -> str:
        """The section number of the part whose record is ``kind``: ``"3.3"``.

        Numbers follow the parts' reading order; an unnumbered part's is empty.
        """
        return section_numbers(self.parts).get(kind, "")

    def to_dict(self) -> dict[str, Any]:
        """The report's numbers as ``report.json`` holds them (SI units, radians)."""
        content: dict[str, Any] = {
            "hexaleg_version": __version__,
            "design": self.design.as_dict(),
        }
        for part in compute_order(self.parts):
            content.update(part.json(self[part.record]))
        numbers: dict[str, Any] = plain(content)
        return numbers


def plain(value: Any) -> Any:
    """NumPy scalars and arrays to plain Python for JSON."""
    if isinstance(value, dict):
        return {str(k): plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain(v) for v in value]
    if isinstance(value, np.ndarray):
        return plain(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    return value


def _no_files(data: ReportData, out: Path) -> None:
    """A part that writes no file."""


def _no_json(record: Any) -> dict[str, Any]:
    """A part with no key in ``report.json``."""
    return {}


Holds = Callable[[Robot, ReportOptions], "LeftOut | None"]
"""Whether a part holds for a robot and the options: ``None``, or what is left out and why."""


def always(robot: Robot, options: ReportOptions) -> LeftOut | None:
    """A part that holds for every robot."""
    return None


def where_legs_are_the_designs(section: str, why: str) -> Holds:
    """A part that holds where every leg is the design's (the paper's leg of l1, l2, l3)."""

    def holds(robot: Robot, options: ReportOptions) -> LeftOut | None:
        return None if robot.own_legs is None else LeftOut(section, why)

    return holds


def where_legs_are_their_own(robot: Robot, options: ReportOptions) -> LeftOut | None:
    """A part that holds where the legs are their own (each by its general leg)."""
    return None if robot.own_legs is not None else LeftOut()


def _no_headline(data: ReportData) -> tuple[str, ...]:
    """A part that says nothing where the command line says where the report is."""
    return ()


@dataclass(frozen=True)
class Part(Generic[R]):
    """One part of the report (see the package docstring for how to add one).

    Attributes:
        record: The type of the frozen record :attr:`compute` returns.
        compute: The record, from the design, options, model and the needed records.
        section: The part's section of the report, from every record (pure); ``None`` for
            a part whose record other sections read and which shows none of its own (the
            designs the report measures, each once).
        needs: Record types of the parts whose records :attr:`compute` reads.
        step: What the progress bar says while computing it.
        files: Writes the part's figures and tables into the report folder.
        json: The part's top-level keys of ``report.json`` (SI units, radians).
        level: Its heading's level: 1 a numbered section, 2 a numbered subsection of the
            section before it, 0 unnumbered.
        holds: Whether it holds for the robot and options (:data:`Holds`).
        headline: The lines the command line prints of it, beside where the report is.

    """

    record: type[R]
    compute: Callable[[ReportData], R]
    section: Callable[[ReportData], Section] | None
    needs: tuple[type, ...] = ()
    step: str = ""
    files: Callable[[ReportData, Path], None] = _no_files
    json: Callable[[R], dict[str, Any]] = _no_json
    level: Level = 1
    holds: Holds = always
    headline: Callable[[ReportData], tuple[str, ...]] = _no_headline


def section_numbers(parts: Sequence[Part[Any]]) -> dict[type, str]:
    """Each numbered part's section number, in reading order: ``"3"``, then ``"3.1"``."""
    numbers: dict[type, str] = {}
    major = minor = 0
    for part in parts:
        if part.level == 1:
            major, minor = major + 1, 0
            numbers[part.record] = str(major)
        elif part.level == 2:
            minor += 1
            numbers[part.record] = f"{major}.{minor}"
    return numbers


def numbered(data: ReportData, part: Part[Any]) -> Section:
    """The part's section, its title numbered (``"3.3 Statics"``, ``"3. Body …"``)."""
    if part.section is None:
        raise HexalegError(f"report part {part.record.__name__} shows no section")
    section = part.section(data)
    number = data.number(part.record)
    if not number:
        return section
    prefix = f"{number}." if part.level == 1 else number
    return replace(section, title=f"{prefix} {section.title}")


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
    robot: Robot | HexapodDesign, options: ReportOptions, parts: Sequence[Part[Any]]
) -> ReportData:
    """Every part's record that holds for ``robot``, each computed from only what it needs.

    A design is hexaleg's template at it. Progress is shown as a study's
    (:class:`~hexaleg.study.progress.Progress`): a bar on a terminal, a line every few
    seconds elsewhere, naming the step that runs.

    Raises:
        RobotImportError: A robot file without masses, before any part is computed.

    """
    robot = as_robot(robot)
    robot.require_masses()  # its statics, walking and decision weigh it: refused up front
    verdicts = [(part, part.holds(robot, options)) for part in parts]
    held = tuple(part for part, left in verdicts if left is None)
    said = tuple(dict.fromkeys(left for _, left in verdicts if left is not None and left.why))
    ordered = compute_order(held)
    with Progress(len(ordered) + 1, unit="steps", show=options.progress) as shown:
        shown.update(0, "model and URDF")
        model = robot.model
        data = ReportData(robot.design, options, model, parts=held, robot=robot, left_out=said)
        for part in ordered:
            shown.update(1, part.step or part.record.__name__)
            data = data.with_record(part.compute(data.only(part.needs)))
        shown.update(1)
    return data


def headline(data: ReportData) -> list[str]:
    """What the command line prints of the report beside where it is, part by part."""
    return [line for part in data.parts for line in part.headline(data)]
