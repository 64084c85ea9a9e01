"""The package's layout (tools/check_layout.py): layers, module and function lengths."""

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


def test_no_upward_import_no_long_module_no_long_function():
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
    (package / "cli" / "run.py").write_text("def f():\n    import hexaleg.robot.model\n")
    found = [str(o) for o in tool.offences(package)]
    assert found == [
        "hexaleg/design.py:2: imports hexaleg.robot (robot) from the design layer",
    ]


def test_the_check_finds_long_modules_and_functions_and_unknown_modules(package):
    tool = _tool()
    body = "\n".join(f"    x{i} = {i}" for i in range(60))
    text = f"def short():\n{body[:-12]}\n\n\ndef long():\n{body}\n"
    (package / "design.py").write_text(text)
    line = text.splitlines().index("def long():") + 1
    cap = tool.MAX_MODULE_LINES
    (package / "limits.py").write_text("\n" * (cap + 1))
    (package / "gadgets.py").write_text("")
    found = [str(o) for o in tool.offences(package)]
    assert found == [
        f"hexaleg/design.py:{line}: function long has 61 lines (> 60)",
        "hexaleg/gadgets.py:1: hexaleg.gadgets is in no layer of tools/check_layout.py",
        f"hexaleg/limits.py:1: module has {cap + 1} lines (> {cap})",
    ]
