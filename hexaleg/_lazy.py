"""Lazy front doors (PEP 562): a package's public names, each imported on first use.

A package's ``__init__`` lists its names and the module that defines each::

    __getattr__, __dir__ = lazy_exports(__name__, {"StudySpec": "hexaleg.study.sweep"})

so importing the package imports none of its modules, and ``hexaleg --help`` or
``hexaleg urdf`` never pay for pandas, Numba or pymoo they do not use. The package keeps
the same names under ``if TYPE_CHECKING:`` for type checkers.
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Mapping
from typing import Any


def lazy_exports(
    package: str, exports: Mapping[str, str]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """A package's module-level ``__getattr__`` and ``__dir__`` for ``exports``.

    Args:
        package: The package's ``__name__``.
        exports: Each public name and the dotted module that defines it.

    Returns:
        ``__getattr__`` imports a name from its module on first use and keeps it in the
        package (later lookups are plain attribute reads); an unknown name raises
        ``AttributeError``, so ``from package import submodule`` still imports the
        submodule. ``__dir__`` lists the package's globals and every export.

    """

    def __getattr__(name: str) -> Any:
        module = exports.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        setattr(sys.modules[package], name, value)
        return value

    def __dir__() -> list[str]:
        return sorted({*vars(sys.modules[package]), *exports})

    return __getattr__, __dir__
