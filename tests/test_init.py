"""The public API: every exported name exists, the list is sorted, versions agree."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

import hexaleg


def test_all_names_exist():
    missing = [name for name in hexaleg.__all__ if not hasattr(hexaleg, name)]
    assert missing == []


def test_all_is_sorted():
    assert hexaleg.__all__ == sorted(hexaleg.__all__)


def test_version_matches_pyproject():
    pyproject = Path(__file__).resolve().parent.parent / "pyproject.toml"
    if pyproject.is_file():
        version = re.search(r'^version = "([^"]+)"', pyproject.read_text(), re.M).group(1)
        assert hexaleg.__version__ == version
    from importlib.metadata import version as installed

    assert installed("hexaleg") == hexaleg.__version__


def test_import_does_no_heavy_work():
    import subprocess
    import sys

    code = "import sys, hexaleg; print('matplotlib' in sys.modules, 'meshcat' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.stdout.split() == ["False", "False"]


def test_cli_import_loads_no_analysis_library():
    """``hexaleg --help`` must stay instant: the CLI front door imports no numerics."""
    import subprocess
    import sys

    heavy = ["numpy", "scipy", "pinocchio", "pandas", "matplotlib", "meshcat", "tqdm"]
    code = f"import sys, hexaleg.cli; print([m for m in {heavy!r} if m in sys.modules])"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


def test_public_names_come_from_their_modules():
    import hexaleg
    from hexaleg.stance.flexibility import flexibility
    from hexaleg.swing.workspace import analyze_workspace

    assert hexaleg.flexibility is flexibility
    assert hexaleg.analyze_workspace is analyze_workspace
    assert "analyze_manipulability" in dir(hexaleg)
    import pytest

    with pytest.raises(AttributeError):
        hexaleg.no_such_name  # noqa: B018


HEAVY = ("matplotlib", "pandas", "pymoo", "mujoco", "meshcat", "numba", "distributed")
"""Libraries a command imports only when it computes or draws, never to parse its options."""

LIGHT_COMMANDS = ("", "actuators", "materials", "workspace", "manipulability")
"""``hexaleg --help`` (``""``) and the commands whose parser stays light. A command's module
imports its analyses at its top (tools/check_layout.py), and only the chosen command's module
is imported: those that measure the stance or size the legs' tubes (design, urdf, flexibility,
loads, gait, simulate, view, explore) import the stance's compiled kernels (Numba) with it;
the sweeping ones (study, report, decide) the study layer."""


def test_building_the_parser_imports_no_heavy_library():
    """``hexaleg --help``, ``hexaleg urdf`` ... start without pandas, Numba, pymoo, meshcat."""
    import subprocess
    import sys

    code = (
        "import importlib, sys\n"
        "main = importlib.import_module('hexaleg.cli.main')\n"
        f"for command in {LIGHT_COMMANDS!r}:\n"
        "    main.build_parser(command)\n"
        f"print(sorted({{m.split('.')[0] for m in sys.modules}} & {set(HEAVY)!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "[]"


LAZY_PACKAGES = (
    "hexaleg",
    "hexaleg.electrical",
    "hexaleg.explore",
    "hexaleg.gait",
    "hexaleg.output.figures",
    "hexaleg.output.viewer",
    "hexaleg.robot",
    "hexaleg.statics",
    "hexaleg.study",
    "hexaleg.swing",
)
"""Every package whose front door is :func:`hexaleg._lazy.lazy_exports`."""


def test_the_lazy_packages_are_all_listed():
    root = Path(hexaleg.__file__).parent
    using = {
        ".".join(("hexaleg", *init.parent.relative_to(root).parts))
        for init in root.rglob("__init__.py")
        if "lazy_exports(__name__)" in init.read_text()
    }
    assert using == set(LAZY_PACKAGES)


@pytest.mark.parametrize("package", LAZY_PACKAGES)
def test_all_is_what_the_type_checking_block_imports(package):
    """``__all__`` and the TYPE_CHECKING imports declare the same names, each from its module."""
    import importlib

    from hexaleg._lazy import type_checking_imports

    module = importlib.import_module(package)
    declared = type_checking_imports(module)
    assert sorted(declared) == sorted(set(module.__all__) - {"__version__"})
    assert len(module.__all__) == len(set(module.__all__))
    for name, source in declared.items():
        assert getattr(module, name) is getattr(importlib.import_module(source), name), name
        assert name in dir(module)
