"""What a design file and the values given over it resolve to, once: the robot, its task.

Every command that takes a design, and the explorer, resolve it here, the same way: the
design file's design, ``[requirements]`` and ``[gait]`` as parsed once
(:class:`~hexaleg.design_file.DesignFile`), the values given over them (the command line's),
and the robot built once from them (:meth:`~hexaleg.robot.robot.Robot.build`): hexaleg's
template at the design, or a robot file, whose body, mounts and stance limits are its own
(:meth:`~hexaleg.robot.robot.Robot.check_over` refuses them given over it). Where the file's
``[structure]`` says ``size = true`` and the caller measures the tubes, the legs' tubes are
sized first, by the caller's sizing (:func:`hexaleg.evaluation.sizing.sized_for`: for the
file's required payload and slope; a caller that does not measure tubes never imports the
search, nor the stance's compiled kernels it runs on). The gait the
robot walks is the file's ``[gait]`` over the robot's own default gait
(:func:`~hexaleg.gait.defaults.default_gait`), found once, when first asked.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import TYPE_CHECKING, Any

from hexaleg.design import HexapodDesign
from hexaleg.design_file import GAIT, REQUIREMENTS, DesignFile
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.gait.defaults import default_gait
from hexaleg.gait.spec import Gait
from hexaleg.robot.recipe import RobotSource
from hexaleg.robot.robot import Robot

if TYPE_CHECKING:  # the result's type only: the search is the caller's (Sizing)
    from hexaleg.structure.sizing import SizedStructure

__all__ = ["IMPORTED", "Inputs", "Posing", "Sizing", "resolve_inputs", "written_requirements"]

IMPORTED = (
    "[structure] describes hexaleg's own legs' tubes; an imported robot keeps its file's "
    "links (remove [structure] from the design file)"
)
"""Why a robot file's design refuses a ``[structure]`` table."""

Sizing = Callable[[HexapodDesign, Requirements], "SizedStructure | None"]
"""How a caller that measures the tubes sizes them: a design's tubes sized for the
requirements where its ``[structure]`` asks, else ``None``
(:func:`hexaleg.evaluation.sizing.sized_for`)."""


Posing = Callable[[Robot, Requirements], Robot]
"""How a caller stands the robot before its tubes are sized: the robot at another posture
for the requirements (``--best-posture``: ``hexaleg posture``'s answer)."""


@dataclass(frozen=True)
class Inputs:
    """What a design file and the values over it resolve to.

    Attributes:
        robot: The robot to analyse, built once (its tubes sized if asked).
        written: The file's ``[requirements]`` as written (none given: nothing required),
            walking the file's ``[gait]`` over :class:`~hexaleg.gait.spec.Gait`'s defaults.
        file: The design file as read, if one was given.
        sized: How the tubes were sized, where the file's ``[structure]`` asked and the
            caller measures them.

    """

    robot: Robot
    written: Requirements
    file: DesignFile | None = None
    sized: SizedStructure | None = None

    @property
    def design(self) -> HexapodDesign:
        """The robot's design."""
        return self.robot.design

    @cached_property
    def default_gait(self) -> Gait:
        """The gait the robot walks without a ``[gait]`` table, found once.

        :class:`Gait`'s defaults for hexaleg's template; a robot file's own, scaled to its
        legs (:func:`~hexaleg.gait.defaults.default_gait`).
        """
        return default_gait(self.robot.model)

    @cached_property
    def gait(self) -> Gait:
        """The gait walked: the file's ``[gait]`` keys over :attr:`default_gait`."""
        base = self.default_gait
        if self.file is None:
            return base
        if base == Gait():  # the file's [gait] over Gait()'s, as read already
            return self.written.walked
        return self.file.table(GAIT, lambda table: Gait.from_table(table, base))

    @property
    def gait_given(self) -> bool:
        """Whether the design file gives a ``[gait]`` table."""
        return self.file is not None and GAIT in self.file.data

    @cached_property
    def requirements(self) -> Requirements:
        """The file's requirements, walking :attr:`gait`."""
        return self.written.walking(self.gait)


def resolve_inputs(
    design: HexapodDesign,
    source: RobotSource,
    file: DesignFile | None = None,
    *,
    given: Mapping[str, Any] | None = None,
    robot_of_file: bool = False,
    posing: Posing | None = None,
    sizing: Sizing | None = None,
) -> Inputs:
    """The robot, requirements and gait of ``design`` built as ``source`` says.

    The file's tables are read the same way whoever asks: a bad ``[requirements]`` or
    ``[gait]`` table, or a ``[structure]`` on a robot file whose links are its own, is
    refused by a caller that does not use it too.

    Args:
        design: The design: the file's (else the default one) with ``given`` set over it.
        source: The robot to build over ``design``: hexaleg's template, or a robot file.
        file: The design file, as read, if there is one.
        given: The design fields given over the file (the command line's), with their
            values: a robot file refuses those it fixes.
        robot_of_file: Whether the robot is the one the file's ``[robot]`` table names (its
            design file was written from it: what the robot file fixes must be its own).
        posing: How the caller stands the robot, before its tubes are sized (they are sized
            for the posture it stands in).
        sizing: The sizing of the legs' tubes, for a caller that measures them: run with
            the file's requirements (it sizes where the ``[structure]`` says
            ``size = true``).

    Raises:
        HexalegError: A bad table, value or robot file, in one line.

    """
    requirements = written_requirements(file)
    robot = Robot.build(source, design)
    robot.check_over(given or {}, file if robot_of_file else None)
    if design.structure is not None and not robot.design_links:
        raise HexalegError(IMPORTED)
    if posing is not None:
        robot = posing(robot, requirements)
    sized = None if sizing is None else sizing(robot.design, requirements)
    if sized is not None:
        robot = Robot.build(source, sized.design)
    return Inputs(robot, requirements, file, sized)


def written_requirements(file: DesignFile | None) -> Requirements:
    """A design file's ``[requirements]`` walking its ``[gait]`` (none: nothing required)."""
    if file is None:
        return Requirements()
    requirements = file.table(REQUIREMENTS, Requirements.from_table)
    return requirements.walking(file.table(GAIT, Gait.from_table))
