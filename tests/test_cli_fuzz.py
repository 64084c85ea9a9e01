"""Every subcommand, driven with arbitrary text and numbers: exit 0 or 2, never a traceback.

On exit 2 the user sees at most one line on stderr and no file is written. The slow
back-ends of ``report``, ``study``, ``view``, ``explore`` and ``simulate`` (minutes of
sweeps, servers that run until Ctrl-C, seconds of physics) are replaced by quick stand-ins: what is
fuzzed is everything in front of them — parsing, validation and the design.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import tempfile
from pathlib import Path
from types import SimpleNamespace

import pandas as pd
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hexaleg.cli import COMMANDS, build_parser
from hexaleg.cli.main import main

PATH_OPTIONS = {"-o", "--output", "--plot", "--html"}
PATHS = st.sampled_from(
    ["out", "out/sub", "out.urdf", "scene.html", "", ".", "nothere/", "n" * 300, "x/" + "n" * 300]
)
"""Output paths: plain ones, and ones a careless user types (empty, the current folder, a
folder where a file is meant, names over the system's 255-byte limit)."""
DESIGN_FILES = {
    "hexagon.toml": 'layout = "hexagon"\nbody_radius = 0.3\nfirst_leg_angle_deg = 20\n',
    "typo.toml": "body_radus = 0.3\n",
    "broken.toml": "l1 = \n",
    "design.json": '{"l1": 0.25, "layout": "rectangle", "middle_leg_offset": 0.1}',
}
"""Design files present in the folder every invocation runs in (read, never written)."""
NUMBERS = st.one_of(
    st.integers(min_value=-(10**13), max_value=10**13).map(str),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.floats(min_value=-2.0, max_value=2.0).map(lambda x: f"{x:.3f}"),
)
TEXT = st.text(alphabet=st.characters(blacklist_categories=("Cs",)), max_size=12)
VALUES = st.one_of(NUMBERS, TEXT)


COMMAND_LINES = [
    *(c.name for c in COMMANDS if c.name != "design"),
    "design init",
    "design show",
    "design import",
]
"""Every command, and each action of the commands that have actions."""


def _parser(command_line: str) -> argparse.ArgumentParser:
    words = command_line.split()
    parser = build_parser(words[0])
    for word in words:
        sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
        parser = sub.choices[word]
    return parser


def _options(command_line: str) -> list[argparse.Action]:
    return [
        action
        for action in _parser(command_line)._actions
        if action.option_strings and not set(action.option_strings) & {"-h", "--help"}
    ]


@st.composite
def invocations(draw, command_line: str) -> list[str]:
    argv = command_line.split()
    for action in _parser(command_line)._actions:
        if not action.option_strings and not isinstance(action, argparse._SubParsersAction):
            argv.append(draw(st.sampled_from(["robot.toml", "robot.json", "sub/robot.toml", ""])))
    for action in draw(st.lists(st.sampled_from(_options(command_line)), max_size=3)):
        argv.append(action.option_strings[-1])
        if action.nargs == 0:
            continue
        count = {None: 1, "+": draw(st.integers(1, 3)), "?": 1}.get(action.nargs, action.nargs)
        if "--design" in action.option_strings:
            source = st.sampled_from([*DESIGN_FILES, "missing.toml", "robot.yaml"])
        else:
            source = PATHS if PATH_OPTIONS & set(action.option_strings) else VALUES
        argv += [draw(source) for _ in range(int(count))]
    return argv


@pytest.fixture(scope="module")
def quick_backends():
    """Stand-ins for the slow back-ends; everything before them runs for real."""
    table = pd.DataFrame(
        [
            {"l1_ratio": 0.1, "l3_ratio": 0.4, "fb": 0.2, "error": ""},
            {"l1_ratio": 0.1, "l3_ratio": 0.5, "fb": 0.21, "error": ""},
        ]
    )
    for axis in ("x", "y", "z", "roll", "pitch", "yaw"):
        table[f"range_{axis}"] = 0.1

    def fake_report(out, design, options):
        from hexaleg.output.report.decision import DecisionRecord
        from hexaleg.output.report.flexibility import FlexibilityRecord
        from hexaleg.output.report.recommendation import RecommendationRecord

        recommendation = SimpleNamespace(l1_ratio=0.1, l2_ratio=0.5, l3_ratio=0.4,
                                         l3_band=(0.3, 0.5))  # fmt: skip
        records = {
            RecommendationRecord: SimpleNamespace(recommendation=recommendation),
            FlexibilityRecord: SimpleNamespace(axis=SimpleNamespace(fb=0.2)),
            DecisionRecord: SimpleNamespace(requirements=None),
        }
        return SimpleNamespace(records=records, parts=())  # no part: no headline to print

    def fake_html(model, result, path, workspace_leg=None, loads=None):
        return Path(path)

    class FakeServer:
        web_url = "http://127.0.0.1:7000/static/"

        def __init__(self, host, port, legend):
            self.host = host

    class FakeExplorer:  # the explorer's page, served until Ctrl-C: returns at once here
        port = 7000

        def __init__(self, session, host, port):
            self.host = host

        def serve_forever(self, poll_interval):
            return None

        def server_close(self):
            return None

    from concurrent.futures import ThreadPoolExecutor

    from hexaleg import HexapodDesign, Objective, Requirements, SearchSettings, decide

    with ThreadPoolExecutor(1) as here:  # a real answer, from a tiny search
        decided = decide(
            HexapodDesign(),
            Requirements(ground_clearance=0.3),
            Objective("improved_area"),
            settings=SearchSettings(evaluations=100),  # five free: 3 lengths, θ2, θ3
            executor=here,
            progress=False,
        )

    from hexaleg.sim import simulate_gait

    walked = simulate_gait(HexapodDesign(), cycles=2)  # a real answer, from a short walk
    patches = {
        "hexaleg.cli.simulate.simulate_gait": lambda *args, **kwargs: walked,
        "hexaleg.cli.simulate._animation": lambda result, model, path: Path(path),
        "hexaleg.cli.simulate._video": lambda result, path: [],
        "hexaleg.cli.decide.decide": lambda *args, **kwargs: decided,
        "hexaleg.cli.report.build_report": fake_report,
        "hexaleg.cli.study.run_study": lambda *args, **kwargs: table,
        "hexaleg.cli.study.write_study_figures": lambda table, out: [],
        "hexaleg.cli.study.sensitivity_table": lambda *args, **kwargs: table,
        "hexaleg.cli.study.write_text": lambda path, text: Path(path),
        "hexaleg.cli.view.write_static_html": fake_html,
        "hexaleg.cli.view.LoopbackServer": FakeServer,
        "hexaleg.cli.view.build_scene": lambda *args, **kwargs: None,
        "hexaleg.cli.view.build_gait_scene": lambda *args, **kwargs: None,
        "hexaleg.cli.view.write_gait_html": fake_html,
        "hexaleg.cli.gait.write_gait_html": fake_html,
        "hexaleg.cli.view.client": lambda server: None,
        "hexaleg.cli.view.serve_until_stopped": lambda server: None,
        "hexaleg.cli.explore.ExplorerServer": FakeExplorer,
    }
    with pytest.MonkeyPatch.context() as monkeypatch:
        for target, value in patches.items():
            monkeypatch.setattr(target, value)
        yield


def _run(argv: list[str]) -> tuple[int, str]:
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        try:
            status = main(argv)
        except SystemExit as exit_:
            status = int(exit_.code or 0)
    return status, err.getvalue()


@pytest.mark.slow  # hypothesis drives every command many times
@pytest.mark.parametrize("command", COMMAND_LINES)
def test_arbitrary_input_is_refused_cleanly_or_accepted(command, quick_backends):
    @settings(
        max_examples=40,
        deadline=None,
        suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
    )
    @given(argv=invocations(command))
    def check(argv: list[str]) -> None:
        with tempfile.TemporaryDirectory() as folder:
            cwd = os.getcwd()
            os.chdir(folder)
            for name, text in DESIGN_FILES.items():
                Path(name).write_text(text)
            try:
                status, err = _run(argv)
                written = sorted(
                    p.name for p in Path(folder).iterdir() if p.name not in DESIGN_FILES
                )
            finally:
                os.chdir(cwd)
        assert status in (0, 2), (argv, status, err)
        assert "Traceback" not in err, (argv, err)
        if status == 2:
            assert err.count("\n") <= 1, (argv, err)
            assert written == [], (argv, written)

    check()
