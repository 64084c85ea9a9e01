"""Check hexaleg's layout: no upward import, no module over 600 lines, no function over 60.

The layers follow DESIGN.md's data flow, lowest first; a module may import its own
layer and those below it, never one above::

    foundation  exceptions, _checks, _typing, _version, _io, _folders, _journal, _compiled,
                _lazy, _input
    design      design, design_file, field_spec, ratios, layouts, limits, leg_geometry,
                kinematics, leg_frames, gravity, cause, actuators, actuator_catalog,
                battery, table_records, grids, design_text, ratings, materials, leg_structure
    numerics    numerics/          (generic: below every analysis)
    robot       robot/
    analysis    swing/, stance/, statics/, gait/, sim/, electrical, structure/
    evaluation  evaluation/        (metrics, requirements, evaluate, goal: the shared vocabulary)
    study       study/, paper/
    output      output/
    explore     explore/           (the live explorer)
    cli         cli/, __main__

``hexaleg/__init__.py`` (the lazy front door) is exempt. Imports inside a function count
as well (they still run upward). Run ``python tools/check_layout.py`` to list every
offence; the exit status is 1 when there is one.
"""

from __future__ import annotations

import ast
import sys
from dataclasses import dataclass
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "hexaleg"

LAYERS: tuple[tuple[str, tuple[str, ...]], ...] = (
    (
        "foundation",
        (
            "exceptions",
            "_checks",
            "_typing",
            "_version",
            "_io",
            "_folders",
            "_journal",
            "_compiled",
            "_lazy",
            "_input",
        ),
    ),
    (
        "design",
        (
            "design",
            "design_file",
            "field_spec",
            "ratios",
            "layouts",
            "limits",
            "leg_geometry",
            "kinematics",
            "leg_frames",
            "gravity",
            "cause",
            "actuators",
            "actuator_catalog",
            "battery",
            "table_records",
            "grids",
            "design_text",
            "ratings",
            "materials",
            "leg_structure",
        ),
    ),
    ("numerics", ("numerics",)),
    ("robot", ("robot",)),
    ("analysis", ("swing", "stance", "statics", "gait", "sim", "electrical", "structure")),
    ("evaluation", ("evaluation",)),
    ("study", ("study", "paper")),
    ("output", ("output",)),
    ("explore", ("explore",)),
    ("cli", ("cli", "__main__")),
)
"""Each layer's name and the top-level modules or packages of ``hexaleg`` in it."""

MAX_MODULE_LINES = 600
"""A module's most lines: a long module that is one concept (every metric's declaration, one
evaluation's steps) beats two halves cut to fit; a module past this is likely two concepts."""
MAX_FUNCTION_LINES = 60


@dataclass(frozen=True)
class Offence:
    """One breach of the layout: where, and what."""

    path: str
    line: int
    what: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.what}"


def layer_of(module: str) -> int | None:
    """Index in :data:`LAYERS` of a dotted ``hexaleg`` module, or ``None`` if unlisted."""
    parts = module.split(".")
    if parts[0] != "hexaleg" or len(parts) < 2:
        return None
    for index, (_, members) in enumerate(LAYERS):
        if parts[1] in members:
            return index
    return None


def module_name(path: Path, package: Path = PACKAGE) -> str:
    """Dotted name of a file of the package."""
    parts = path.relative_to(package.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def imported_modules(tree: ast.Module, module: str, is_package: bool) -> list[tuple[str, int]]:
    """Every ``hexaleg`` module ``tree`` imports (at any depth), with its line."""
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            found += [(alias.name, node.lineno) for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:  # relative: resolve against this module's package
                package = module.split(".")
                package = package if is_package else package[:-1]
                base = ".".join([*package[: len(package) - node.level + 1], base]).rstrip(".")
            found.append((base, node.lineno))
    return [(name, line) for name, line in found if name.split(".")[0] == "hexaleg"]


def check_file(path: Path, package: Path = PACKAGE) -> list[Offence]:
    """Every offence of one module: upward imports, its length, its long functions."""
    text = path.read_text(encoding="utf-8")
    where = str(path.relative_to(package.parent))
    offences = []
    lines = len(text.splitlines())
    if lines > MAX_MODULE_LINES:
        offences.append(Offence(where, 1, f"module has {lines} lines (> {MAX_MODULE_LINES})"))
    tree = ast.parse(text)
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            length = (node.end_lineno or node.lineno) - node.lineno + 1
            if length > MAX_FUNCTION_LINES:
                what = f"function {node.name} has {length} lines (> {MAX_FUNCTION_LINES})"
                offences.append(Offence(where, node.lineno, what))
    module = module_name(path, package)
    own = layer_of(module)
    if path.name == "__init__.py" and path.parent == package:
        return offences  # the lazy front door re-exports from every layer
    if own is None:
        return [*offences, Offence(where, 1, f"{module} is in no layer of tools/check_layout.py")]
    for imported, line in imported_modules(tree, module, path.name == "__init__.py"):
        target = layer_of(imported)
        if target is not None and target > own:
            what = f"imports {imported} ({LAYERS[target][0]}) from the {LAYERS[own][0]} layer"
            offences.append(Offence(where, line, what))
    return offences


def offences(package: Path = PACKAGE) -> list[Offence]:
    """Every offence in the package, file by file."""
    return [o for path in sorted(package.rglob("*.py")) for o in check_file(path, package)]


def main() -> int:
    """Print every offence; exit status 1 if there is one."""
    found = offences()
    for offence in found:
        print(offence)
    print(f"{len(found)} offence(s)", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
