"""The public robot files kept for the tests, and how the tests run a command on one.

Kraby (MIT, its meshes kept) and Kevin Ochs's PhantomX (BSD, no meshes, no foot: the tests
give its foot offset) are under ``tests/data/robots``, each with its source and licence.

:data:`KINDS` are the two kinds of robot every analysis takes: hexaleg's template at the
default design and a robot file (Kraby); a test of a behaviour both share is parametrized
over them (:func:`robot_of`).
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import pytest
from conftest import run_cli
from robot_files import draw_hexapod

from hexaleg.design import HexapodDesign
from hexaleg.exceptions import RobotImportWarning
from hexaleg.limits import STANCE_LIMITS
from hexaleg.robot.recipe import RobotSource
from hexaleg.robot.robot import Robot

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = str(ROBOTS / "kraby" / "hexapod.urdf")
OCHS = str(ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro")
OCHS_OFFSET = (0.0, 0.133, 0.0)
"""PhantomX draws no foot: the foot point in each tibia's frame [m]."""


KINDS = ("template", "kraby")
"""Each kind of robot: hexaleg's template at the default design, and a robot file."""


def robot_of(kind: str, design: HexapodDesign | None = None) -> Robot:
    """The robot of a kind, over ``design`` (the default design); the file's placeholders
    not warned about."""
    source = RobotSource() if kind == "template" else RobotSource.of(KRABY)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        return Robot.build(source, design)


def robot_argv(kind: str) -> list[str]:
    """The command-line options that choose the robot of a kind."""
    return [] if kind == "template" else ["--urdf", KRABY]


def robot_json(capsys: pytest.CaptureFixture[str], argv: list[str]) -> dict:
    """A command's ``--json`` (given in ``argv``), the files' placeholder masses not warned."""
    capsys.readouterr()  # what was printed before is not this command's
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(argv) == 0
    return json.loads(capsys.readouterr().out)


def robot_under_test(path: str, tmp_path: Path) -> tuple[str, list[str], tuple | None]:
    """The file, its options and its foot offset; ``drawn:N`` draws six equal general legs.

    ``ochs`` names PhantomX (with its foot offset), any other text a robot file itself.
    """
    if path == "ochs":
        return OCHS, ["--foot-offset", *map(str, OCHS_OFFSET)], OCHS_OFFSET
    if path.startswith("drawn:"):  # hip height, lateral offset, mixed signs, bends
        target = tmp_path / "drawn.urdf"
        target.write_text(draw_hexapod(int(path.split(":")[1]), same_legs=True)[0])
        return str(target), [], None
    return path, [], None


def equal_limits_design(layout: str) -> HexapodDesign:
    """A design whose four joint-limit sets are the stance's: its URDF's limits are the stance's.

    Its template URDF imported back then has the design's own stance limits, so that every
    analysis of the imported robot must equal the design's.
    """
    limits = STANCE_LIMITS
    return HexapodDesign(
        layout=layout,
        workspace_limits=limits,
        improved_limits=limits,
        manipulability_limits=limits,
        stance_limits=limits,
    )
