"""An imported robot in the explorer: its segments slide, its body and ratings are the file's.

The page's length sliders change every leg's coxa, femur and tibia along their own lines
(:meth:`~hexaleg.robot.imported_model.ImportedHexapodModel.with_design`); the posture,
payload and gait sliders act as on hexaleg's robot. The body's size and the motors are the
file's, so a query setting them is refused, naming the key. "save design" writes a design
file that ``--design`` reads back as this robot: the robot file's ``[robot]`` table with the
slid lengths as ``[robot.segments]``, the design's own ``l1 l2 l3`` kept at the file's.
"""

from __future__ import annotations

import os
import threading
from collections import OrderedDict
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import tomli_w

from hexaleg.design import HexapodDesign
from hexaleg.design_text import design_toml
from hexaleg.exceptions import ParameterError
from hexaleg.explore.query import ACTUATOR_KEYS, DESIGN_KEYS
from hexaleg.leg_geometry import SEGMENT_NAMES
from hexaleg.robot.imported_model import ImportedHexapodModel

__all__ = ["ExploredRobot"]

SLID_KEYS = ("l1", "l2", "l3", "nominal_angles")
"""The design keys a query sets on an imported robot: its segments and posture. Every other
design key (its body, mounts, masses, limits, ratings, motors) is its file's."""

CACHED_MODELS = 32
"""Models of recent segment lengths kept (a slider dragged back and forth reuses them)."""


@dataclass(frozen=True)
class ExploredRobot:
    """An imported robot as loaded, and how its design file is written back.

    Attributes:
        model: Its model at the loaded segments (the design file's ``[robot.segments]``
            and ``--l*`` applied).
        table: The design file's ``[robot]`` table without its ``segments``: the robot file
            and package folders (absolute paths), how it is read, what was read.
        file_lengths: The segments (l1, l2, l3) as the robot file draws them [m].

    """

    model: ImportedHexapodModel
    table: Mapping[str, Any]
    file_lengths: tuple[float, float, float]
    _models: OrderedDict[HexapodDesign, ImportedHexapodModel] = field(
        default_factory=OrderedDict, compare=False, repr=False
    )
    _lock: threading.Lock = field(default_factory=threading.Lock, compare=False, repr=False)

    @property
    def source(self) -> str:
        """The robot file, as the page names it."""
        return str(self.model.robot.source)

    def model_for(self, design: HexapodDesign) -> ImportedHexapodModel:
        """The robot at ``design``'s segments and posture (the latest ones kept)."""
        with self._lock:  # the server answers requests in threads
            found = self._models.get(design)
            if found is None:
                found = self.model.with_design(design)
                self._models[design] = found
                while len(self._models) > CACHED_MODELS:
                    self._models.popitem(last=False)
            self._models.move_to_end(design)
            return found

    def refuse_fixed(self, params: Mapping[str, str]) -> None:
        """Refuse a query setting what the robot file fixes (any design key but :data:`SLID_KEYS`).

        Raises:
            ParameterError: Naming the first such key.

        """
        for key in params:
            if (key in DESIGN_KEYS or key in ACTUATOR_KEYS) and key not in SLID_KEYS:
                raise ParameterError(
                    key,
                    params[key],
                    "not for an imported robot: its body, masses, limits and ratings are its "
                    "file's (the explorer slides its segments, posture, payload and gait)",
                )

    def design_text(self, design: HexapodDesign, at: Path | None = None) -> str:
        """The design file of the robot at ``design``'s segments and posture (TOML).

        ``at``: where the file is written, its paths then relative to its folder (a file
        written elsewhere, a job's, keeps them absolute).
        """
        l1, l2, l3 = self.file_lengths
        written = design.replace(l1=l1, l2=l2, l3=l3)  # the file's, as read
        segments = dict(zip(SEGMENT_NAMES, design.lengths, strict=True))
        if l1 <= 0:  # a coxa of length 0 has nothing to stretch: it stays the file's
            segments.pop("coxa")
        table = {**self.table, "segments": segments}
        if at is not None:
            folder = at.resolve().parent
            table["urdf"] = os.path.relpath(table["urdf"], folder)
            packages = table["packages"]
            table["packages"] = {name: os.path.relpath(packages[name], folder) for name in packages}
        return design_toml(written) + "\n" + tomli_w.dumps({"robot": table})
