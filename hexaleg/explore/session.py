"""What an explorer serves: the loaded robot, its conditions and requirements, where it saves.

The session is what the page resets to and what every query starts from; it answers
:func:`~hexaleg.explore.answer.answer` for a query on the loaded robot at the query's
design (:meth:`~hexaleg.robot.robot.Robot.at`: a robot file's segments change along its
legs' own lines, its body and motors stay the file's, and a query setting them is refused),
and writes a design file that reads back as that robot through hexaleg's output mechanism
(:func:`hexaleg._io.write_text`: atomically, a temporary file beside it, then a rename),
the loaded ``[requirements]`` kept.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import tomli_w

from hexaleg._io import check_output_file, write_text
from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.design import DESIGN_FIELDS, HexapodDesign
from hexaleg.evaluation.evaluate import Conditions
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.metrics import objectives
from hexaleg.evaluation.requirement_specs import WALKING_SLOPE
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError, ParameterError
from hexaleg.explore.answer import answer, feet_reach, loaded_values
from hexaleg.explore.cloud import Cloud
from hexaleg.explore.jobs import Jobs, job_options
from hexaleg.explore.query import (
    ACTUATOR_KEYS,
    DESIGN_KEYS,
    POSTURE_KEYS,
    SLOPE_LIMIT,
    Query,
    parse_query,
)
from hexaleg.gait.spec import Gait
from hexaleg.robot.robot import POSTURE_FIELD, Robot
from hexaleg.study.posture import DEFAULT_OBJECTIVE

__all__ = ["Session"]

SLIDERS: tuple[tuple[str, str, float, float], ...] = (
    ("l1", "coxa l1 [m]", 0.25, 2.0),
    ("l2", "femur l2 [m]", 0.25, 2.0),
    ("l3", "tibia l3 [m]", 0.25, 2.0),
    ("body_length", "body length [m]", 0.5, 1.5),
    ("body_width", "body width [m]", 0.5, 1.5),
)
"""Length sliders: key, label, and their range as fractions of the loaded value."""

CATALOG_COLUMNS = ("name", "manufacturer", "model", "peak_torque", "continuous_torque", "mass")
"""What the page's motor choices show of each catalog entry."""


class SaveTarget:
    """Where "save design" writes, and whether a file already there may be replaced.

    A file the user named (``--save``, a ``--design`` file) or allowed (``--force``) is
    replaced whatever it holds; otherwise (the default ``design.toml``) only a file this
    explorer wrote itself is: none there, it is made; one it did not write (another
    inode or modification time than its last save left) is refused.

    Args:
        path: The design file (.toml).
        replace: Whether a file there may be replaced whoever wrote it.

    """

    def __init__(self, path: Path, replace: bool) -> None:
        self.path, self.replace = path, replace
        self._written: tuple[int, int] | None = None  # (inode, mtime [ns]) of its last save
        self._lock = threading.Lock()

    def write(self, text: str) -> Path:
        """Write ``text`` to :attr:`path` (atomically), unless it would replace another's file.

        Raises:
            ParameterError: ``save``: a file is there that this explorer did not write.

        """
        with self._lock:
            if not self.replace:
                self._refuse_another_file()
            path = write_text(self.path, text)
            found = os.stat(path)
            self._written = (found.st_ino, found.st_mtime_ns)
            return path

    def _refuse_another_file(self) -> None:
        try:
            found = os.stat(self.path)
        except FileNotFoundError:
            return
        if (found.st_ino, found.st_mtime_ns) != self._written:
            raise ParameterError(
                "save",
                str(self.path),
                "the file exists and this explorer did not write it: start hexaleg explore "
                "with --save FILE to name the file to write, or --force to replace it",
            )


@dataclass(frozen=True)
class Session:
    """One explorer's loaded inputs.

    Attributes:
        robot: The loaded robot (what reset returns to): hexaleg's template at the loaded
            design, or a robot file as loaded (``--urdf``, or a design file's ``[robot]``).
        conditions: The loaded conditions: the requirements' payload, slope and gait when
            the file has them, else level ground, no payload and the file's ``[gait]``
            (the default gait without one).
        requirements: The design file's requirements, as written (none given: nothing is
            checked); a leg length not required is the loaded design's.
        save_to: The design file "save design" writes (.toml).
        target: How it writes it (a file it did not write replaced only when allowed).
        cloud: The study's cloud around the loaded design, measured in the background.
        jobs: Its long jobs (free-coupled search, decide), each another process.

    """

    robot: Robot
    conditions: Conditions
    requirements: Requirements
    save_to: Path
    target: SaveTarget = field(compare=False)
    cloud: Cloud = field(compare=False)
    jobs: Jobs = field(default_factory=Jobs, compare=False)

    @classmethod
    def start(
        cls,
        robot: Robot,
        requirements: Requirements,
        save_to: str | Path,
        *,
        replace: bool = True,
    ) -> Session:
        """The session of a loaded robot.

        ``replace``: whether "save design" may replace a file at ``save_to`` it did not
        write (the user named the file, or said ``--force``).

        Raises:
            HexalegError: A robot without masses (its payloads and torques need them),
                or a file to save to that is not TOML: refused before serving.

        """
        robot.require_masses()
        path = check_output_file(save_to)
        if path.suffix.lower() != ".toml":
            raise HexalegError(f"{path}: the design is saved as TOML, the file must end in .toml")
        conditions = Goal(requirements.resolved(robot.design)).conditions
        cloud = Cloud(robot, conditions).start()
        return cls(robot, conditions, requirements, path, SaveTarget(path, replace), cloud)

    @property
    def design(self) -> HexapodDesign:
        """The loaded design (the robot's)."""
        return self.robot.design

    def query(self, params: Mapping[str, str]) -> Query:
        """The design and conditions a query asks for (a ParameterError names a bad key).

        A key the robot fixes (a robot file's body, masses, limits, ratings, motors) is
        refused, naming it.
        """
        for key in params:
            if (key in DESIGN_KEYS or key in ACTUATOR_KEYS) and not self._takes(key):
                raise ParameterError(
                    key,
                    params[key],
                    "not for an imported robot: its body, masses, limits and ratings are its "
                    "file's (the explorer slides its segments, posture, payload and gait)",
                )
        return parse_query(params, self.design, self.conditions)

    def _takes(self, key: str) -> bool:
        """Whether the robot takes a query's key (a motor's: its ``actuators``)."""
        return self.robot.takes("actuators" if key in ACTUATOR_KEYS else key)

    def robot_at(self, params: Mapping[str, str]) -> tuple[Query, Robot]:
        """The query, and the loaded robot at the design it asks for."""
        asked = self.query(params)
        return asked, self.robot.at(asked.design)

    def evaluate(self, params: Mapping[str, str]) -> dict[str, Any]:
        """The page's numbers for the design a query asks for (one evaluation).

        Where its ``[structure]`` says ``size = true``, the evaluation sizes its tubes first,
        for the sliders' payload and the requirements' slope; the answer's
        ``structure.sizing`` says how.
        """
        asked, robot = self.robot_at(params)
        required = self.requirements
        if required.given:  # the leg length the loaded design has, unless the file says
            required = required.resolved(self.design)
        return answer(robot.design, asked.conditions, required, robot.model, asked.ground)

    def reach(self, params: Mapping[str, str]) -> dict[str, Any]:
        """Each foot's reach on the ground for the design a query asks for (``reach``)."""
        robot = self.robot_at(params)[1]
        return {"reach": feet_reach(robot.design, robot.model)}

    def loaded(self) -> dict[str, Any]:
        """What the page starts at and resets to: values, sliders, motors, requirements."""
        values = loaded_values(self.design, self.conditions)
        shown = [s for s in SLIDERS if self.robot.takes(s[0])]
        ranges = {
            key: [low * values[key], high * values[key], label] for key, label, low, high in shown
        }
        bounds = {spec.key: spec.bounds for spec in DESIGN_FIELDS if spec.bounds is not None}
        limits = self.design.stance_limits
        posture = {key: list(getattr(limits, key)) for key in POSTURE_KEYS}
        motors = [{key: entry.to_dict()[key] for key in CATALOG_COLUMNS}
                  for entry in shipped_catalog()]  # fmt: skip
        return {
            "values": values,
            "catalog": motors,
            "has_actuators": self.design.actuators is not None,
            "sliders": ranges,
            "posture": posture,
            "slope_deg": [-SLOPE_LIMIT, SLOPE_LIMIT],
            "objectives": {better: objectives(better) for better in ("maximize", "minimize")},
            "posture_objective": f"{DEFAULT_OBJECTIVE.sense}={DEFAULT_OBJECTIVE.name}",
            "posture_search": self.robot.searches(POSTURE_FIELD),
            "bounds": bounds,
            "requirements": self.requirements.to_dict(),
            "save_to": str(self.save_to),
            "robot": self.robot.source.path,
        }

    def design_text(self, params: Mapping[str, str], at: Path | None = None) -> str:
        """The design file (TOML) of the design a query asks for, the requirements kept.

        The sliders' gait is its ``[gait]`` table (none for the default gait); the payload
        is a condition, not part of a design, so it is not written. A slope slid
        (``slope_deg``) is the ``[requirements]``' ``walking_slope``, which the file declares
        as the slope the robot must walk (up, down and across it: :data:`WALKING_SLOPE`);
        level ground, none. ``at``: where the file is written (an imported robot's file
        paths relative to it).
        """
        asked, robot = self.robot_at(params)
        text, gait = robot.design_text(at), asked.conditions.gait
        if gait != Gait():
            text += "\n" + gait.to_toml()
        table = self.requirements.to_dict()
        if asked.ground is not None:
            table.pop(WALKING_SLOPE.name, None)
            if not asked.ground.level:
                table[WALKING_SLOPE.name] = abs(asked.ground.slope)
        if table:
            text += "\n" + tomli_w.dumps({"requirements": table})
        return text

    def save(self, params: Mapping[str, str]) -> Path:
        """Write the design a query asks for to :attr:`save_to`; the requirements kept."""
        return self.target.write(self.design_text(params, self.save_to))

    def start_job(self, kind: str, params: Mapping[str, str]) -> dict[str, Any]:
        """Start the long job ``kind`` on the design a query asks for.

        ``kind``: ``free``, ``posture`` or ``decide`` (:data:`~.jobs.JOB_KINDS`); the
        posture's objective is the query's ``maximize`` or ``minimize`` (:func:`job_options`).
        """
        asked = dict(params)
        options = job_options(kind, asked)
        return self.jobs.start(kind, self.design_text(asked), options).to_dict()

    def job(self, kind: str) -> dict[str, Any]:
        """The latest job of ``kind``: its state and progress (``state`` ``none``: never run)."""
        found = self.jobs.get(kind)
        return {"kind": kind, "state": "none"} if found is None else found.to_dict()
