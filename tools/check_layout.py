"""Check hexaleg's layout: layers, no import cycle, imports at the top, short functions.

The layers follow DESIGN.md's data flow, lowest first; a module may import its own
layer and those below it, never one above::

    foundation  exceptions, _checks, _typing, _version, _io, _folders, _journal, _compiled,
                _lazy, _input
    design      design, design_file, field_spec, ratios, layouts, limits, leg_geometry,
                kinematics, leg_frames, gravity, cause, actuators, actuator_catalog,
                battery, table_records, catalog_file, grids, design_text, ratings, materials,
                leg_structure, field_sweep
    numerics    numerics/          (generic: below every analysis)
    robot       robot/
    analysis    swing/, stance/, statics/, gait/, sim/, electrical, structure/
    evaluation  evaluation/        (metrics, requirements, evaluate, goal: the shared vocabulary)
    study       study/, paper/
    output      output/
    explore     explore/           (the live explorer)
    cli         cli/, __main__

What the check refuses, module by module:

- **An upward import**: a module importing a layer above its own. ``hexaleg/__init__.py``
  (the lazy front door) is exempt.
- **An import cycle**: modules that import each other, directly or through others. Every
  import counts, wherever it is written: at the top, inside a function, or under
  ``if TYPE_CHECKING:`` (a cycle a type checker sees is still two concepts that each need
  the other; the fix is to put the concept where both can import it). ``from a.b import c``
  imports ``a.b`` (and ``a.b.c`` when that is a module): a package whose ``__init__`` holds
  code is a module like any other.
- **A hexaleg module imported inside a function**: such an import hides an upward import
  or a cycle from a reader, and from the interpreter until the function first runs. Every
  hexaleg import is at the top of its module; a command's module imports its analyses
  there, since ``hexaleg`` imports only the chosen command's module. Two places import by
  name instead, and are not import statements: ``cli/main.py``'s dispatch
  (:func:`importlib.import_module` over its table of commands, so that ``hexaleg --help``
  imports no command) and the packages' lazy front doors (:mod:`hexaleg._lazy`: a name is
  imported from the module its ``TYPE_CHECKING`` import names, which the cycle check reads).
  Heavy third-party packages (matplotlib, meshcat, mujoco, weasyprint, distributed, pandas
  where only a figure needs it) may still be imported inside the function that needs them:
  the check is about hexaleg's own modules only. :data:`LOCAL_IMPORTS_ALLOWED` would list
  an exception with its reason; it is empty.
- **A function over** :data:`MAX_FUNCTION_LINES` **lines**: a function that does not fit
  on a screen is a sign the piece wants splitting.

There is no cap on a module's length. Caps of 400, then 500 and 600 lines made modules split
where the count ran out rather than where the concept ends (a gait's limits in three
modules, a class's properties moved beside it); a module is one concept however long, and
what the check can see of a second concept inside it is its imports: a cycle, or an import
from a layer it should not need.

Run ``python tools/check_layout.py`` to list every offence; the exit status is 1 when there
is one.
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
            "catalog_file",
            "grids",
            "design_text",
            "ratings",
            "materials",
            "leg_structure",
            "field_sweep",
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

MAX_FUNCTION_LINES = 60
"""A function's most lines (its signature, docstring and body)."""

LOCAL_IMPORTS_ALLOWED: dict[tuple[str, str], str] = {}
"""``(module, imported)`` pairs allowed inside a function, each with its reason: none."""


@dataclass(frozen=True)
class Offence:
    """One breach of the layout: where, and what."""

    path: str
    line: int
    what: str

    def __str__(self) -> str:
        return f"{self.path}:{self.line}: {self.what}"


@dataclass(frozen=True)
class Import:
    """One import statement's hexaleg module, where it is written.

    Attributes:
        module: The dotted module it imports, as written (``hexaleg.robot.model``).
        names: The names it takes from ``module`` (``from module import a, b``); empty for
            ``import module``.
        line: Its line.
        local: Whether it is written inside a function.

    """

    module: str
    names: tuple[str, ...]
    line: int
    local: bool


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


def imports(tree: ast.Module, module: str, is_package: bool) -> list[Import]:
    """Every import of a ``hexaleg`` module in ``tree``, at any depth, in the order written."""
    found: list[Import] = []

    def visit(node: ast.AST, local: bool) -> None:
        for child in ast.iter_child_nodes(node):
            inner = local or isinstance(child, ast.FunctionDef | ast.AsyncFunctionDef | ast.Lambda)
            if isinstance(child, ast.Import):
                found.extend(Import(a.name, (), child.lineno, local) for a in child.names)
            elif isinstance(child, ast.ImportFrom):
                names = tuple(alias.name for alias in child.names)
                found.append(
                    Import(_absolute(child, module, is_package), names, child.lineno, local)
                )
            visit(child, inner)

    visit(tree, False)
    return [i for i in found if i.module.split(".")[0] == "hexaleg"]


def _absolute(node: ast.ImportFrom, module: str, is_package: bool) -> str:
    """The module a ``from ... import`` names, a relative one resolved against ``module``."""
    base = node.module or ""
    if not node.level:
        return base
    package = module.split(".")
    package = package if is_package else package[:-1]
    return ".".join([*package[: len(package) - node.level + 1], base]).rstrip(".")


def imported_modules(tree: ast.Module, module: str, is_package: bool) -> list[tuple[str, int]]:
    """Every ``hexaleg`` module ``tree`` imports (at any depth), with its line."""
    return [(i.module, i.line) for i in imports(tree, module, is_package)]


def check_file(path: Path, package: Path = PACKAGE) -> list[Offence]:
    """Every offence of one module but cycles: upward and local imports, long functions."""
    text = path.read_text(encoding="utf-8")
    where = str(path.relative_to(package.parent))
    offences = []
    tree = ast.parse(text)
    for node in ast.walk(tree):
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
            length = (node.end_lineno or node.lineno) - node.lineno + 1
            if length > MAX_FUNCTION_LINES:
                what = f"function {node.name} has {length} lines (> {MAX_FUNCTION_LINES})"
                offences.append(Offence(where, node.lineno, what))
    module = module_name(path, package)
    found = imports(tree, module, path.name == "__init__.py")
    for item in found:
        if item.local and (module, item.module) not in LOCAL_IMPORTS_ALLOWED:
            what = f"imports {item.module} inside a function (hexaleg's imports go at the top)"
            offences.append(Offence(where, item.line, what))
    own = layer_of(module)
    if path.name == "__init__.py" and path.parent == package:
        return offences  # the lazy front door re-exports from every layer
    if own is None:
        return [*offences, Offence(where, 1, f"{module} is in no layer of tools/check_layout.py")]
    for item in found:
        target = layer_of(item.module)
        if target is not None and target > own:
            what = f"imports {item.module} ({LAYERS[target][0]}) from the {LAYERS[own][0]} layer"
            offences.append(Offence(where, item.line, what))
    return offences


Graph = dict[str, dict[str, int]]
"""Each module's imported modules of the package, each with the line of its first import."""


def import_graph(package: Path = PACKAGE) -> tuple[Graph, dict[str, Path]]:
    """Which module of the package imports which (every import counts), and their files.

    ``from a.b import c`` is an edge to ``a.b``, and to ``a.b.c`` when that is a module.
    """
    files = {module_name(path, package): path for path in sorted(package.rglob("*.py"))}
    graph: Graph = {}
    for module, path in files.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        edges: dict[str, int] = {}
        for item in imports(tree, module, path.name == "__init__.py"):
            targets = [item.module, *(f"{item.module}.{name}" for name in item.names)]
            for target in targets:
                while target and target not in files:  # a name of a module: that module
                    target = target.rpartition(".")[0]
                if target and target != module:
                    edges.setdefault(target, item.line)
        graph[module] = edges
    return graph, files


def cycles(graph: Graph) -> list[list[str]]:
    """Every import cycle: each strongly connected set of two or more modules, as a path.

    Each is given as one cycle through all of its set's first module (in sorted order),
    ``[a, b, ..., a]``, the shortest back to it.
    """
    found = []
    for members in _strongly_connected(graph):
        if len(members) > 1:
            found.append(_shortest_cycle(graph, min(members), members))
    return sorted(found)


def _strongly_connected(graph: Graph) -> list[set[str]]:
    """Tarjan's strongly connected components, iteratively (no recursion limit)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components: list[set[str]] = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, successors = work[-1]
            step = next(successors, None)
            if step is None:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = set()
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.add(member)
                        if member == node:
                            break
                    components.append(component)
            elif step not in index:
                index[step] = low[step] = len(index)
                stack.append(step)
                on_stack.add(step)
                work.append((step, iter(sorted(graph.get(step, {})))))
            elif step in on_stack:
                low[node] = min(low[node], index[step])
    return components


def _shortest_cycle(graph: Graph, start: str, members: set[str]) -> list[str]:
    """The shortest path from ``start`` back to itself within ``members`` (breadth first)."""
    previous: dict[str, str] = {}
    frontier = [start]
    while frontier:
        following = []
        for node in frontier:
            for step in sorted(graph[node]):
                if step == start:
                    path = [node]
                    while path[-1] != start:
                        path.append(previous[path[-1]])
                    return [start, *reversed(path[:-1]), start] if node != start else [start, start]
                if step in members and step not in previous:
                    previous[step] = node
                    following.append(step)
        frontier = following
    raise ValueError(f"{start} is on no cycle")  # pragma: no cover - a component of 2+ is


def cycle_offences(package: Path = PACKAGE) -> list[Offence]:
    """One offence per import cycle, at the import that leaves its first module."""
    graph, files = import_graph(package)
    offences = []
    for cycle in cycles(graph):
        first, second = cycle[0], cycle[1]
        where = str(files[first].relative_to(package.parent))
        what = "import cycle: " + " -> ".join(cycle)
        offences.append(Offence(where, graph[first][second], what))
    return offences


def offences(package: Path = PACKAGE) -> list[Offence]:
    """Every offence in the package, file by file, then every import cycle."""
    found = [o for path in sorted(package.rglob("*.py")) for o in check_file(path, package)]
    return found + cycle_offences(package)


def main() -> int:
    """Print every offence; exit status 1 if there is one."""
    found = offences()
    for offence in found:
        print(offence)
    print(f"{len(found)} offence(s)", file=sys.stderr)
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
