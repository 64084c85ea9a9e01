"""A continuous leg joint: analysed as a revolute one over [−π, π], every angle once.

Oracle: the same drawn robot written with that joint revolute and limited to [−π, π] by the
test itself; every analysis of the whole robot must give the same numbers on both files.
"""

from __future__ import annotations

import json
import math
import re
import warnings

import pytest
from conftest import run_cli
from robot_files import draw_hexapod

from hexaleg.exceptions import RobotImportWarning

HIP = re.compile(r'(<joint name="\w+_j2" type=")revolute(">.*?<limit) lower="[^"]*" upper="[^"]*"')


def _files(tmp_path):
    """The drawn robot with continuous hips, and the same with revolute hips over ±π."""
    text, _ = draw_hexapod(7, same_legs=True)
    continuous = HIP.sub(r"\1continuous\2", text)
    bounded = HIP.sub(rf'\1revolute\2 lower="{-math.pi!r}" upper="{math.pi!r}"', text)
    assert continuous.count('type="continuous"') == 6 and bounded != text
    paths = tmp_path / "continuous.urdf", tmp_path / "bounded.urdf"
    for path, written in zip(paths, (continuous, bounded), strict=True):
        path.write_text(written)
    return paths


def _json(capsys, argv):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli([*argv, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("command", ["flexibility", "loads"])
def test_a_continuous_hip_is_analysed_as_a_revolute_one_over_plus_minus_pi(
    tmp_path, capsys, command
):
    continuous, bounded = _files(tmp_path)
    found = _json(capsys, [command, "--urdf", str(continuous)])
    expected = _json(capsys, [command, "--urdf", str(bounded)])
    found.pop("robot"), expected.pop("robot")
    assert found == expected
