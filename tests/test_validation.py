"""Hostile and careless input: one short line naming the field.

None of these may end in a traceback from deep inside (OverflowError, TypeError,
RecursionError, MemoryError), a hang, or a study that runs and fails every design.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys

import pytest
from conftest import run_cli
from hypothesis import given, settings
from hypothesis import strategies as st

from hexaleg import HexapodDesign, JointLimits, LegMount, analyze_manipulability, analyze_workspace
from hexaleg.design import DESIGN_FIELDS
from hexaleg.exceptions import MAX_VALUE_CHARS, HexalegError, ParameterError, shorten
from hexaleg.swing.workspace import monte_carlo_workspace

MAX_MESSAGE_CHARS = 400
"""Longest one-line message a user should ever see for one bad value."""


def _one_short_line(message: str) -> None:
    assert "\n" not in message.strip(), message
    assert len(message) <= MAX_MESSAGE_CHARS, message[:500]


def _refused_in_one_line(capsys, argv: list[str], *fragments: str) -> str:
    assert run_cli(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err, err[:2000]
    _one_short_line(err)
    for fragment in fragments:
        assert fragment in err, err
    return err


# -- a study grid that leaves a segment out of range is refused up front ----------

STUDY_GRIDS = {
    "tiny coxa ratio": (
        ["--l1-ratios", "1e-300"],
        ["--l1-ratios = 1e-300", "coxa", "[0.001, 100]"],
    ),
    "coxa under a millimetre": (["--l1-ratios", "0.0005"], ["--l1-ratios = 0.0005", "0.0005 m"]),
    "tiny total": (["--total", "0.003"], ["l1_ratios", "at total 0.003 m"]),
    "huge total": (["--total", "250"], ["l3_ratios = 0.75", "tibia would be 188 m"]),
    "a ratio twice": (["--l1-ratios", "0.1", "0.1"], ["--l1-ratios = 0.1", "given twice"]),
    "no room for the femur": (["--l1-ratios", "0.9"], ["must leave room for femur and tibia"]),
}


@pytest.mark.parametrize(("argv", "fragments"), STUDY_GRIDS.values(), ids=STUDY_GRIDS.keys())
def test_study_grids_that_cannot_be_built_are_refused_before_running(
    tmp_path, capsys, argv, fragments
):
    out = tmp_path / "study"
    command = ["study", *argv, "-o", str(out), "--l3-points", "2", "--workers", "1"]
    _refused_in_one_line(capsys, command, *fragments)
    assert not out.exists()


def test_the_grid_check_accepts_the_papers_grid_and_every_design_on_it_builds():
    from hexaleg.design import SEGMENT_RANGE, l3_ratio_grid
    from hexaleg.paper import L1_RATIOS
    from hexaleg.ratios import require_ratio_grid

    assert require_ratio_grid(L1_RATIOS, tuple(l3_ratio_grid()), 1.0) is None
    # the oracle: constructing each design at the grid's corners, every segment in range
    lower, upper = SEGMENT_RANGE
    for r1 in L1_RATIOS:
        for r3 in l3_ratio_grid(5):
            design = HexapodDesign.from_ratios(r1, r3, 1.0)
            assert all(lower <= length <= upper for length in design.lengths)
            assert design.leg_length == pytest.approx(1.0, abs=1e-12)
    # and a grid whose largest ratios leave no femur is not accepted
    with pytest.raises(ParameterError, match="femur"):
        require_ratio_grid((*L1_RATIOS, 0.9), (0.1,), 1.0)


# -- design files that are not files, too large, or absurd inside ----------------


def _design_show(path) -> list[str]:
    return ["design", "show", "--design", str(path)]


def test_a_fifo_is_refused_without_waiting_for_a_writer(tmp_path):
    fifo = tmp_path / "robot.toml"
    os.mkfifo(fifo)
    result = subprocess.run(
        [sys.executable, "-m", "hexaleg", *_design_show(fifo)],
        capture_output=True,
        text=True,
        timeout=120,  # a wait for a writer would hang here
    )
    assert result.returncode == 2
    assert "not a regular file" in result.stderr and "Traceback" not in result.stderr


def test_a_link_to_a_device_is_refused_without_reading_it(tmp_path, capsys):
    link = tmp_path / "robot.toml"
    link.symlink_to("/dev/zero")  # endless: reading it would exhaust the memory
    _refused_in_one_line(capsys, _design_show(link), "not a regular file")


def test_a_file_over_the_size_cap_is_refused(tmp_path, capsys):
    from hexaleg.design_file import MAX_FILE_BYTES

    path = tmp_path / "robot.toml"
    with path.open("wb") as file:
        file.truncate(MAX_FILE_BYTES + 1)  # sparse: costs no disk
    _refused_in_one_line(capsys, _design_show(path), "larger than 16 MiB")


ABSURD_FILES = {
    "1 and 400 zeros": (
        "robot.toml",
        "l1 = 1" + "0" * 400 + "\n",
        ["l1 = <an integer", "[0, 100]"],
    ),
    "5000 digits, TOML": ("robot.toml", "l1 = " + "9" * 5000 + "\n", ["Exceeds the limit"]),
    "5000 digits, JSON": ("robot.json", '{"l1": ' + "9" * 5000 + "}", ["Exceeds the limit"]),
    "nested, TOML": ("robot.toml", "l1 = " + "[" * 100_000 + "]" * 100_000, ["nested"]),
    "nested, JSON": ("robot.json", '{"l1": ' + "[" * 100_000 + "]" * 100_000 + "}", ["nested"]),
    "a million angles": (
        "robot.toml",
        "nominal_angles = [" + ", ".join(["0.5"] * 1_000_000) + "]\n",
        ["nominal_angles = [0.5, 0.5", "...", "3 numbers"],
    ),
    "degrees overflow": ("robot.toml", "front_yaw_deg = 1" + "0" * 400 + "\n", ["front_yaw_deg"]),
    "huge mount": (
        "robot.toml",
        'layout = "custom"\n[[mount]]\nname = "a"\nx = 1' + "0" * 400 + "\ny = 0\nz = 0\nyaw = 0\n",
        ["mounts[a].x", "[-100, 100] [m]"],
    ),
}


@pytest.mark.parametrize(("name", "text", "fragments"), ABSURD_FILES.values(), ids=ABSURD_FILES)
def test_absurd_numbers_and_nesting_in_a_file_give_one_short_line(
    tmp_path, capsys, name, text, fragments
):
    path = tmp_path / name
    path.write_text(text)
    _refused_in_one_line(capsys, _design_show(path), str(path), *fragments)


# -- the API names the field at construction, never a Python error from deep inside


API_CASES = {
    "l1 = 10**400": (lambda: HexapodDesign(l1=10**400), "l1", "must lie in [0, 100] [m]"),
    "l1 = -10**400": (lambda: HexapodDesign(l1=-(10**400)), "l1", "must lie in"),
    "stance_limits None": (
        lambda: HexapodDesign(stance_limits=None),
        "stance_limits",
        "must be a JointLimits",
    ),
    "workspace_limits 'x'": (
        lambda: HexapodDesign(workspace_limits="x"),
        "workspace_limits",
        "must be a JointLimits",
    ),
    "nominal_angles 5": (
        lambda: HexapodDesign(nominal_angles=5),
        "nominal_angles",
        "must be 3 numbers [rad]: theta1, theta2, theta3",
    ),
    "nominal_angles text": (lambda: HexapodDesign(nominal_angles="abc"), "nominal_angles", "3"),
    "rated_torques text": (  # None is valid: not given (a robot file's effort of 0)
        lambda: HexapodDesign(rated_torques="abc"),
        "rated_torques",
        "root, hip, knee",
    ),
    "rated_speeds a dict": (lambda: HexapodDesign(rated_speeds={}), "rated_speeds", "3 numbers"),
    "rated_torques nested": (
        lambda: HexapodDesign(rated_torques=([1.0], 2.0, 3.0)),
        "rated_torques.root",
        "real number",
    ),
    "layout a list": (lambda: HexapodDesign(layout=["hexagon"]), "layout", "use one of"),
    "mounts a string": (lambda: HexapodDesign(mounts="abcdef"), "mounts", "LegMount"),
    "limits as text": (
        lambda: JointLimits("ab", (0.0, 1.0), (-1.0, 0.0)),
        "custom.theta1",
        "must be 2 angles",
    ),
    "limits name": (lambda: JointLimits((0, 1), (0, 1), (-1, 0), name=3), "JointLimits.name", ""),
    "mount yaw 10**400": (lambda: LegMount("a", 0, 0, 0, 10**400), "mounts[a].yaw", "[rad]"),
    "analyze_workspace(None)": (lambda: analyze_workspace(None), "design", "a HexapodDesign"),
    "analyze_manipulability(5)": (lambda: analyze_manipulability(5), "design", "a HexapodDesign"),
    "samples '100'": (
        lambda: monte_carlo_workspace(HexapodDesign(), samples="100"),
        "samples",
        "must be an integer",
    ),
    "samples 1.5": (
        lambda: monte_carlo_workspace(HexapodDesign(), samples=1.5),
        "samples",
        "integer",
    ),
    "samples 0": (lambda: monte_carlo_workspace(HexapodDesign(), samples=0), "samples", "1.."),
    "seed 'x'": (lambda: monte_carlo_workspace(HexapodDesign(), seed="x"), "seed", "integer"),
    "limits 'x'": (lambda: monte_carlo_workspace(HexapodDesign(), limits="x"), "limits", ""),
}


@pytest.mark.parametrize(("call", "field", "allowed"), API_CASES.values(), ids=API_CASES)
def test_the_api_refuses_bad_values_naming_the_field(call, field, allowed):
    with pytest.raises(ParameterError) as info:
        call()
    assert info.value.field == field
    assert allowed in str(info.value)
    assert str(info.value).startswith(f"{field} = ")
    _one_short_line(str(info.value))


def test_a_million_element_value_gives_a_short_message():
    with pytest.raises(ParameterError) as info:
        HexapodDesign(nominal_angles=[0.5] * 1_000_000)
    assert str(info.value) == (
        "nominal_angles = [0.5, 0.5, 0.5, 0.5, 0.5, 0.5, ...] is not valid: "
        "must be 3 numbers [rad]: theta1, theta2, theta3"
    )
    assert info.value.value == [0.5] * 1_000_000  # the data is kept, only the text is short


@pytest.mark.parametrize(
    ("value", "text"),
    [
        (0.1 + 0.2, "0.3"),
        ((0.2, 0.4, -1.5707963267948966), "(0.2, 0.4, -1.5708)"),
        (10**5000, "<an integer of about 5001 digits>"),
        ("x" * 1000, "'" + "x" * 37),
        (float("nan"), "nan"),
        (None, "None"),
    ],
    ids=["float", "floats", "huge int", "long text", "nan", "None"],
)
def test_shorten_keeps_values_readable_and_bounded(value, text):
    shown = shorten(value)
    assert shown.startswith(text)
    assert len(shown) <= MAX_VALUE_CHARS and "\n" not in shown


def test_shorten_survives_deep_nesting_and_hostile_reprs():
    deep: list = []
    for _ in range(100_000):
        deep = [deep]

    class Hostile:
        def __repr__(self) -> str:
            raise RuntimeError("no")

    assert shorten(deep) == "[[[...]]]"
    assert shorten(Hostile()).startswith("<Hostile")


def test_the_old_design_error_name_still_works():
    from hexaleg.exceptions import DesignError

    error = DesignError("l1", 5.0, "must lie in [0.001, 100] [m]")
    assert isinstance(error, ParameterError) and isinstance(error, ValueError)
    assert str(error) == "l1 = 5 is not valid: must lie in [0.001, 100] [m]"
    import pickle

    assert str(pickle.loads(pickle.dumps(error))) == str(error)  # crosses process pools


# -- every field, fuzzed with values of every type ------------------------------------------

ANY_VALUE = st.recursive(
    st.none()
    | st.booleans()
    | st.integers(min_value=-(10**500), max_value=10**500)
    | st.floats(allow_nan=True, allow_infinity=True)
    | st.text(max_size=20)
    | st.binary(max_size=5)
    | st.sampled_from([math.pi, -0.3, 0.25, 3, (0.0, 0.0, -1.5), object()]),
    lambda inner: (
        st.lists(inner, max_size=4)
        | st.tuples(inner, inner, inner)
        | st.dictionaries(st.text(max_size=3), inner, max_size=2)
    ),
    max_leaves=8,
)


@settings(max_examples=300, deadline=None)
@given(field=st.sampled_from([spec.name for spec in DESIGN_FIELDS]), value=ANY_VALUE)
def test_any_value_of_any_field_is_accepted_or_refused_in_one_line(field, value):
    try:
        HexapodDesign(**{field: value})
    except HexalegError as err:
        assert isinstance(err, ParameterError)
        _one_short_line(str(err))
    # anything but a HexalegError (TypeError, OverflowError, ...) fails the test
