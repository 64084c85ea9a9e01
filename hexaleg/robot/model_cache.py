"""What depends on a design's body only, made once per body: its model, its body's shape.

Rendering the URDF through Xacro and parsing it costs far more than every analysis of
a design that follows. What a length, a rating or the nominal posture changes is set on
a copy of a model of the same body by :meth:`~hexaleg.robot.model.HexapodModel.with_design`
(exact: the tests hold it equal to the model built from the URDF). :func:`model_of`
derives each design's model from its body's, built once; :func:`per_body` keeps anything
else that only the body determines (the body's collision shape), for the last few bodies
used in this process.
"""

from __future__ import annotations

import threading
from collections import OrderedDict
from collections.abc import Callable
from dataclasses import fields
from typing import Any, TypeVar

from hexaleg.design import HexapodDesign
from hexaleg.robot.model import DERIVED_FIELDS, HexapodModel

__all__ = ["KEPT", "body_key", "model_of", "per_body"]

T = TypeVar("T")

KEPT = 32
"""Things kept, all bodies together (the least recently used is dropped first)."""

_KEPT: OrderedDict[tuple[str, tuple[Any, ...]], Any] = OrderedDict()
_LOCK = threading.RLock()


def model_of(design: HexapodDesign) -> HexapodModel:
    """``design``'s model: derived from its body's model when one was built, else built.

    The model returned is the caller's own (a copy): nothing done to it reaches the
    kept one.
    """
    return per_body("model", design, lambda: HexapodModel(design)).with_design(design)


def per_body(what: str, design: HexapodDesign, make: Callable[[], T]) -> T:
    """``what`` of ``design``'s body: made by ``make`` the first time, then the one kept.

    Args:
        what: The name of the thing (one body has one of each).
        design: A design of the body.
        make: Makes it; it must depend on the body only (no field in
            :data:`~hexaleg.robot.model.DERIVED_FIELDS`), and the caller must not change it.

    """
    key = (what, body_key(design))
    with _LOCK:
        if key in _KEPT:
            _KEPT.move_to_end(key)
            return _KEPT[key]
        made = make()
        _KEPT[key] = made
        while len(_KEPT) > KEPT:
            _KEPT.popitem(last=False)
        return made


def body_key(design: HexapodDesign) -> tuple[Any, ...]:
    """What a body's things depend on: every design field but those a derived model sets."""
    return tuple(getattr(design, f.name) for f in fields(design) if f.name not in DERIVED_FIELDS)
