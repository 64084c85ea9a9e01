"""The package's layout (tools/check_layout.py): layers, cycles, local imports, long functions."""

from __future__ import annotations

import importlib.util
import sys
from pathlib import Path

import pytest

TOOL = Path(__file__).resolve().parents[1] / "tools" / "check_layout.py"


def _tool():
    spec = importlib.util.spec_from_file_location("check_layout", TOOL)
    module = importlib.util.module_from_spec(spec)
    sys.modules["check_layout"] = module  # dataclasses look their module up
    spec.loader.exec_module(module)
    return module


def test_no_upward_import_no_cycle_no_local_import_no_long_function():
    offences = _tool().offences()
    listed = "\n".join(map(str, offences))
    print(listed)
    assert offences == [], f"{len(offences)} offence(s):\n{listed}"


@pytest.fixture
def package(tmp_path):
    root = tmp_path / "hexaleg"
    for folder in ("", "robot", "cli"):
        (root / folder).mkdir(exist_ok=True)
        (root / folder / "__init__.py").write_text("")
    return root


def test_the_check_finds_an_upward_import(package):
    tool = _tool()
    (package / "design.py").write_text("import math\nfrom hexaleg.robot import model\n")
    (package / "robot" / "model.py").write_text("from hexaleg.design import x\n")
    found = [str(o) for o in tool.offences(package)]
    assert found == [
        "hexaleg/design.py:2: imports hexaleg.robot (robot) from the design layer",
        "hexaleg/design.py:2: import cycle: hexaleg.design -> hexaleg.robot.model "
        "-> hexaleg.design",
    ]


def test_the_check_finds_long_functions_and_unknown_modules_not_long_modules(package):
    tool = _tool()
    body = "\n".join(f"    x{i} = {i}" for i in range(60))
    text = f"def short():\n{body[:-12]}\n\n\ndef long():\n{body}\n"
    (package / "design.py").write_text(text)
    line = text.splitlines().index("def long():") + 1
    (package / "limits.py").write_text("x = 1\n" * 5000)  # one concept however long
    (package / "gadgets.py").write_text("")
    found = [str(o) for o in tool.offences(package)]
    assert found == [
        f"hexaleg/design.py:{line}: function long has 61 lines (> 60)",
        "hexaleg/gadgets.py:1: hexaleg.gadgets is in no layer of tools/check_layout.py",
    ]


def test_a_cycle_hidden_under_type_checking_or_in_a_function_is_found(package):
    tool = _tool()
    (package / "robot" / "model.py").write_text(
        "from typing import TYPE_CHECKING\n\nif TYPE_CHECKING:\n"
        "    from hexaleg.robot.urdf import render\n"
    )
    (package / "robot" / "urdf.py").write_text("from hexaleg.robot.legs import Leg\n")
    (package / "robot" / "legs.py").write_text("def leg():\n    from hexaleg.robot import model\n")
    found = [str(o) for o in tool.offences(package)]
    assert found == [
        "hexaleg/robot/legs.py:2: imports hexaleg.robot inside a function "
        "(hexaleg's imports go at the top)",
        "hexaleg/robot/legs.py:2: import cycle: hexaleg.robot.legs -> hexaleg.robot.model "
        "-> hexaleg.robot.urdf -> hexaleg.robot.legs",
    ]


def test_each_cycle_is_named_once_by_its_shortest_loop(package):
    tool = _tool()
    files = {  # two cycles: a <-> b, and c -> d -> e -> c with a shortcut d -> c
        "a": "from hexaleg.robot import b",
        "b": "import hexaleg.robot.a",
        "c": "from hexaleg.robot.d import x",
        "d": "from hexaleg.robot.e import y\nfrom hexaleg.robot.c import z",
        "e": "from hexaleg.robot.c import w",
    }
    for name, text in files.items():
        (package / "robot" / f"{name}.py").write_text(text + "\n")
    graph, _ = tool.import_graph(package)
    assert graph["hexaleg.robot.a"] == {"hexaleg.robot": 1, "hexaleg.robot.b": 1}
    assert tool.cycles(graph) == [
        ["hexaleg.robot.a", "hexaleg.robot.b", "hexaleg.robot.a"],
        ["hexaleg.robot.c", "hexaleg.robot.d", "hexaleg.robot.c"],
    ]


def test_a_package_init_that_imports_its_module_back_is_a_cycle(package):
    tool = _tool()
    (package / "cli" / "__init__.py").write_text("from hexaleg.cli.run import main\n")
    (package / "cli" / "run.py").write_text("from hexaleg.cli import helpers\n")
    (package / "cli" / "helpers.py").write_text("")
    (package / "cli" / "other.py").write_text("import hexaleg.cli.helpers as helpers\n")
    assert [str(o) for o in tool.offences(package)] == [
        "hexaleg/cli/__init__.py:1: import cycle: hexaleg.cli -> hexaleg.cli.run -> hexaleg.cli",
    ]


def test_only_hexaleg_modules_must_be_imported_at_the_top(package, monkeypatch):
    tool = _tool()
    (package / "cli" / "run.py").write_text(
        "import json\n\n\ndef plot():\n    import matplotlib\n\n\n"
        "def run():\n    from hexaleg.design import x\n\n\n"
        "class Later:\n    def go(self):\n        return lambda: __import__('os')\n"
    )
    (package / "design.py").write_text("")
    local = "hexaleg/cli/run.py:9: imports hexaleg.design inside a function"
    assert [str(o) for o in tool.offences(package)] == [
        f"{local} (hexaleg's imports go at the top)"
    ]
    monkeypatch.setitem(tool.LOCAL_IMPORTS_ALLOWED, ("hexaleg.cli.run", "hexaleg.design"), "why")
    assert tool.offences(package) == []
