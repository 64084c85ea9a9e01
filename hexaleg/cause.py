"""What binds: the one constraint that stops a search, named with its leg, joint and bound.

Every analysis that stops at a constraint (a body extreme, a payload capacity, a slope,
a gait's limit, a requirement) says which one with a :class:`Cause`, so that tables,
JSON and figures name it the same way.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg._typing import CauseKind, require_choice


@dataclass(frozen=True)
class Cause:
    """The constraint that binds.

    Attributes:
        kind: ``"joint"`` (a joint limit), ``"reach"`` (foothold out of the leg's
            reach), ``"ground"`` (the body touches the ground, or with ``leg`` that
            leg's knee does), ``"collision"`` (two of the robot's own parts touch),
            ``"range"`` (nothing broke within the searched range), ``"torque"`` or
            ``"speed"`` (a joint at its rated torque or speed), ``"continuous_torque"``
            (a joint's RMS torque at its actuator's continuous torque), ``"voltage"`` (the
            voltage its motor needs at the bus voltage), ``"tip"`` (the gravity
            line leaves the support polygon on a slope), ``"slide"`` (the slope's
            tangent reaches the friction coefficient; with ``leg``, that standing foot's
            force leaves the friction cone walking), ``"stability"`` (the centre of
            mass leaves the support polygon), ``"zmp"`` (a gait's zero-moment point leaves
            the standing feet's polygon), ``"search limit"`` (nothing binds below the
            search's own bound), ``"strength"`` (a leg tube's stress at its strength /
            safety factor) or ``"deflection"`` (a foot's deflection at its limit).
        leg: Leg name, for joint, reach, torque, speed, voltage and a leg's ground and
            slide causes.
        joint: ``"root"``, ``"hip"`` or ``"knee"``, for joint, torque, speed and voltage causes.
        bound: ``"lower"``/``"upper"`` for joints, ``"outer"``/``"inner"`` for reach.
        links: The two links that touch, for collision causes.
        segment: ``"coxa"``, ``"femur"`` or ``"tibia"``, for strength causes.

    """

    kind: CauseKind
    leg: str | None = None
    joint: str | None = None
    bound: str | None = None
    links: tuple[str, str] | None = None
    segment: str | None = None

    def __str__(self) -> str:
        if self.kind == "joint":
            return f"{self.leg} {self.joint} joint at its {self.bound} limit"
        if self.kind == "reach":
            edge = "too far" if self.bound == "outer" else "too close"
            return f"{self.leg} foothold out of reach ({edge})"
        if self.kind == "ground":
            return f"{self.leg} knee touches the ground" if self.leg else "body touches the ground"
        if self.kind == "collision" and self.links:
            return f"{self.links[0]} touches {self.links[1]}"
        if self.kind in ("torque", "speed", "continuous_torque"):
            return f"{self.leg} {self.joint} {self.kind.replace('_', ' ')} at its rating"
        if self.kind == "voltage":
            return f"{self.leg} {self.joint} motor's voltage at the supply's"
        if self.kind == "slide" and self.leg:
            return f"{self.leg} foot slides (friction cone)"
        if self.kind == "strength":
            return f"{self.leg} {self.segment} at its strength / safety factor"
        if self.kind == "deflection":
            return f"{self.leg} foot's deflection at its limit"
        if self.kind == "zmp":
            return "ZMP leaves the support polygon"
        if self.kind in ("tip", "slide", "stability", "search limit"):
            return self.kind
        return "end of the searched range"

    def same_constraint_as(self, other: Cause) -> bool:
        """Whether ``other`` is the same kind of constraint, perhaps on another leg."""
        same = (self.kind, self.joint, self.bound) == (other.kind, other.joint, other.bound)
        return same and self.kind != "collision"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form, with its one-line ``description``."""
        return {
            "kind": self.kind,
            "leg": self.leg,
            "joint": self.joint,
            "bound": self.bound,
            "links": list(self.links) if self.links else None,
            "segment": self.segment,
            "description": str(self),
        }

    @classmethod
    def from_dict(cls, record: Any) -> Cause:
        """The cause :meth:`to_dict` wrote (its ``description`` is derived, not read).

        Raises:
            ValueError: ``record`` is not such a dict, or a field has the wrong type.

        """
        if not isinstance(record, dict):
            raise ValueError("a cause is a JSON object")
        names = {key: record.get(key) for key in ("leg", "joint", "bound", "segment")}
        links = record.get("links")
        pair = links is None or (isinstance(links, list) and len(links) == 2)
        texts = [*names.values(), *(links if isinstance(links, list) else [])]
        if not pair or not all(text is None or isinstance(text, str) for text in texts):
            raise ValueError("a cause names its leg, joint, bound, segment and links in text")
        kind = require_choice("kind", record.get("kind"), CauseKind)
        return cls(kind, **names, links=None if links is None else (links[0], links[1]))
