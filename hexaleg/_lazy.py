"""Lazy front doors (PEP 562): a package's public names, each imported on first use.

A package's ``__init__`` declares each public name once where type checkers, the docs
and this module all read it, in an import under ``if TYPE_CHECKING:``, lists the names
in ``__all__``, and ends with::

    __getattr__, __dir__ = lazy_exports(__name__)

The imports never run: on the first name asked for that the package does not hold,
:func:`type_checking_imports` reads them from the package's source, and the name is
imported from its module then. Importing the package imports none of its modules, so
``hexaleg --help`` or ``hexaleg urdf`` never pay for pandas, Numba or pymoo they do not
use. The tests hold every ``__all__`` to its package's imports.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable
from functools import cache
from types import ModuleType
from typing import Any


def lazy_exports(package: str) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """A package's module-level ``__getattr__`` and ``__dir__`` for its declared names.

    Args:
        package: The package's ``__name__``.

    Returns:
        ``__getattr__`` imports a name from its module on first use and keeps it in the
        package (later lookups are plain attribute reads); an unknown name raises
        ``AttributeError``, so ``from package import submodule`` still imports the
        submodule. ``__dir__`` lists the package's globals and every export.

    """

    @cache
    def exports() -> dict[str, str]:
        return type_checking_imports(sys.modules[package])

    def __getattr__(name: str) -> Any:
        module = exports().get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted({*vars(sys.modules[package]), *exports()})

    return __getattr__, __dir__


def type_checking_imports(module: ModuleType) -> dict[str, str]:
    """Each name ``module`` imports under ``if TYPE_CHECKING:``, and the module it is from.

    Read from the module's source (``from a.b import C`` gives ``{"C": "a.b"}``).
    """
    import ast  # only when a lazy name is first asked for

    spec = module.__spec__
    get_source = getattr(spec.loader, "get_source", None) if spec is not None else None
    source = None if get_source is None or spec is None else get_source(spec.name)
    if source is None:
        raise ImportError(f"{module.__name__}: its source, which declares its names, is missing")
    names: dict[str, str] = {}
    for node in ast.parse(source).body:
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING":
            for statement in node.body:
                if isinstance(statement, ast.ImportFrom) and statement.module:
                    for alias in statement.names:
                        names[alias.asname or alias.name] = statement.module
    return names
