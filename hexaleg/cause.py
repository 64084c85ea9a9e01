"""What binds: the one constraint that stops a search, named with its leg, joint and bound.

Every analysis that stops at a constraint (a body extreme, a payload capacity, a slope,
a gait's limit, a requirement) says which one with a :class:`Cause`, so that tables,
JSON and figures name it the same way.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from hexaleg._typing import CauseKind


@dataclass(frozen=True)
class Cause:
    """The constraint that stops the body.

    Attributes:
        kind: ``"joint"`` (a joint limit), ``"reach"`` (foothold out of the leg's
            reach), ``"ground"`` (the body touches the ground), ``"collision"`` (two of
            the robot's own parts touch) or ``"range"`` (nothing broke within the
            searched range).
        leg: Leg name, for joint and reach causes.
        joint: ``"root"``, ``"hip"`` or ``"knee"``, for joint causes.
        bound: ``"lower"``/``"upper"`` for joints, ``"outer"``/``"inner"`` for reach.
        links: The two links that touch, for collision causes.

    """

    kind: CauseKind
    leg: str | None = None
    joint: str | None = None
    bound: str | None = None
    links: tuple[str, str] | None = None

    def __str__(self) -> str:
        if self.kind == "joint":
            return f"{self.leg} {self.joint} joint at its {self.bound} limit"
        if self.kind == "reach":
            edge = "too far" if self.bound == "outer" else "too close"
            return f"{self.leg} foothold out of reach ({edge})"
        if self.kind == "ground":
            return "body touches the ground"
        if self.kind == "collision" and self.links:
            return f"{self.links[0]} touches {self.links[1]}"
        return "end of the searched range"

    def same_constraint_as(self, other: Cause) -> bool:
        """Whether ``other`` is the same kind of constraint, perhaps on another leg."""
        same = (self.kind, self.joint, self.bound) == (other.kind, other.joint, other.bound)
        return same and self.kind != "collision"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready form."""
        return {
            "kind": self.kind,
            "leg": self.leg,
            "joint": self.joint,
            "bound": self.bound,
            "links": list(self.links) if self.links else None,
        }
