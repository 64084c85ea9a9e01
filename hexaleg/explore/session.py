"""What an explorer serves: the loaded design, its conditions and requirements, where it saves.

The session is what the page resets to and what every query starts from; it answers
:func:`~hexaleg.explore.answer.answer` for a query, and writes a design file through
hexaleg's output mechanism (:func:`hexaleg._io.write_text`: atomically, a temporary file
beside it, then a rename), the loaded ``[requirements]`` kept.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import tomli_w

from hexaleg._io import check_output_file, write_text
from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.design import DESIGN_FIELDS, HexapodDesign
from hexaleg.design_text import design_toml
from hexaleg.evaluation.evaluate import Conditions
from hexaleg.evaluation.goal import Goal
from hexaleg.evaluation.requirements import Requirements
from hexaleg.exceptions import HexalegError
from hexaleg.explore.answer import answer, feet_reach, loaded_values
from hexaleg.explore.cloud import Cloud
from hexaleg.explore.jobs import Jobs
from hexaleg.explore.query import Query, parse_query
from hexaleg.explore.robot import SLID_KEYS, ExploredRobot
from hexaleg.gait.spec import Gait
from hexaleg.robot.model import HexapodModel

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


@dataclass(frozen=True)
class Session:
    """One explorer's loaded inputs.

    Attributes:
        design: The loaded design (what reset returns to).
        conditions: The loaded conditions: the requirements' payload, slope and gait when
            the file has them, else level ground, no payload and the file's ``[gait]``
            (the default gait without one).
        requirements: The design file's requirements, as written (none given: nothing is
            checked); a leg length not required is the loaded design's.
        save_to: The design file "save design" writes (.toml).
        cloud: The study's cloud around the loaded design, measured in the background.
        jobs: Its long jobs (free-coupled search, decide), each another process.
        robot: The imported robot explored (``--urdf``, or a design file's ``[robot]``),
            ``None`` for hexaleg's own.

    """

    design: HexapodDesign
    conditions: Conditions
    requirements: Requirements
    save_to: Path
    cloud: Cloud = field(compare=False)
    jobs: Jobs = field(default_factory=Jobs, compare=False)
    robot: ExploredRobot | None = field(default=None, compare=False)

    @classmethod
    def start(
        cls,
        design: HexapodDesign,
        requirements: Requirements,
        save_to: str | Path,
        robot: ExploredRobot | None = None,
    ) -> Session:
        """The session of a loaded design (an imported robot's: ``robot.model.design``)."""
        path = check_output_file(save_to)
        if path.suffix.lower() != ".toml":
            raise HexalegError(f"{path}: the design is saved as TOML, the file must end in .toml")
        conditions = (
            Goal(requirements.resolved(design)).conditions
            if requirements.given
            else Conditions(gait=requirements.walked)
        )
        models = None if robot is None else robot.model.with_design  # uncached: its own thread
        cloud = Cloud(design, conditions, models).start()
        return cls(design, conditions, requirements, path, cloud, robot=robot)

    def query(self, params: Mapping[str, str]) -> Query:
        """The design and conditions a query asks for (a ParameterError names a bad key)."""
        if self.robot is not None:
            self.robot.refuse_fixed(params)
        return parse_query(params, self.design, self.conditions)

    def model_for(self, design: HexapodDesign) -> HexapodModel | None:
        """The imported robot at ``design``'s segments; ``None``: hexaleg's template's."""
        return None if self.robot is None else self.robot.model_for(design)

    def evaluate(self, params: Mapping[str, str]) -> dict[str, Any]:
        """The page's numbers for the design a query asks for."""
        asked = self.query(params)
        required = self.requirements
        if required.given:  # the leg length the loaded design has, unless the file says
            required = required.resolved(self.design)
        model = self.model_for(asked.design)
        design = asked.design if model is None else model.design
        return answer(design, asked.conditions, required, model)

    def reach(self, params: Mapping[str, str]) -> dict[str, Any]:
        """Each foot's reach on the ground for the design a query asks for (``reach``)."""
        design = self.query(params).design
        model = self.model_for(design)
        return {"reach": feet_reach(design if model is None else model.design, model)}

    def loaded(self) -> dict[str, Any]:
        """What the page starts at and resets to: values, sliders, motors, requirements."""
        values = loaded_values(self.design, self.conditions)
        shown = [s for s in SLIDERS if self.robot is None or s[0] in SLID_KEYS]
        ranges = {
            key: [low * values[key], high * values[key], label] for key, label, low, high in shown
        }
        bounds = {spec.key: spec.bounds for spec in DESIGN_FIELDS if spec.bounds is not None}
        motors = [{key: entry.to_dict()[key] for key in CATALOG_COLUMNS}
                  for entry in shipped_catalog()]  # fmt: skip
        return {
            "values": values,
            "catalog": motors,
            "has_actuators": self.design.actuators is not None,
            "sliders": ranges,
            "bounds": bounds,
            "requirements": self.requirements.to_dict(),
            "save_to": str(self.save_to),
            "robot": None if self.robot is None else self.robot.source,
        }

    def design_text(self, params: Mapping[str, str], at: Path | None = None) -> str:
        """The design file (TOML) of the design a query asks for, the requirements kept.

        The sliders' gait is its ``[gait]`` table (none for the default gait); the payload
        is a condition, not part of a design, so it is not written. ``at``: where the file
        is written (an imported robot's file paths relative to it).
        """
        asked = self.query(params)
        design, robot, gait = asked.design, self.robot, asked.conditions.gait
        text = design_toml(design) if robot is None else robot.design_text(design, at)
        if gait != Gait():
            text += "\n" + gait.to_toml()
        if self.requirements.given:
            text += "\n" + tomli_w.dumps({"requirements": self.requirements.to_dict()})
        return text

    def save(self, params: Mapping[str, str]) -> Path:
        """Write the design a query asks for to :attr:`save_to`; the requirements kept."""
        return write_text(self.save_to, self.design_text(params, self.save_to))

    def start_job(self, kind: str, params: Mapping[str, str]) -> dict[str, Any]:
        """Start the long job ``kind`` (``free`` or ``decide``) on the design a query asks for."""
        return self.jobs.start(kind, self.design_text(params)).to_dict()

    def job(self, kind: str) -> dict[str, Any]:
        """The latest job of ``kind``: its state and progress (``state`` ``none``: never run)."""
        found = self.jobs.get(kind)
        return {"kind": kind, "state": "none"} if found is None else found.to_dict()
