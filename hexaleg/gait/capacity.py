"""The largest payload a design carries walking a gait, exactly: what binds, and at what mass.

A payload m at a fixed point of the body (default: the centre of its top face) changes
nothing in a gait period but the loads: the body moves level at constant velocity, so the
payload's weight is its only force, and the generalized forces of the free-flyer model are
affine in m. The minimum-norm foot forces are linear in them, so every joint torque is
affine in m as well, τ(m) = τ₀ + m·Δτ, and so are the base wrench and, once multiplied by
the vertical force F_z(m) > 0, the zero-moment point's side of every edge of the standing
feet's polygon. Two walks of the gait — unloaded and with 1 kg — give τ₀, Δτ and the
wrench's two parts, and every constraint becomes a bound on m:

- each joint at each sample: |τ₀ + m·Δτ| ≤ its rated torque;
- each edge of the support polygon at each sample: the ZMP on its inner side;
- the joint speeds and the gait's own constraints (reach, joint limits, the ground) do not
  depend on m: broken unloaded, the design cannot walk the gait at all (capacity 0).

The capacity is the smallest of those bounds (at most
:data:`~hexaleg.statics.forces.PAYLOAD_SEARCH_LIMIT`), and the constraint that gives it is
what binds. No search and no bisection: the tests hold it against a bisection on
:func:`~hexaleg.gait.analysis.analyze_gait`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.gait.spec import Gait
from hexaleg.gait.walk import Loads, Walker
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.forces import GRAVITY, PAYLOAD_SEARCH_LIMIT, Payload
from hexaleg.statics.support import SupportPolygon

PROBE_MASS = 1.0
"""The payload of the second walk [kg]: any positive mass gives the same affine maps."""


@dataclass(frozen=True)
class WalkingCapacity:
    """The largest payload walked within the ratings, and what binds.

    Attributes:
        mass: The payload [kg]; 0 when the design cannot walk the gait unloaded.
        limited_by: What binds at that payload (a joint's torque, the ZMP leaving the
            support polygon), or what stops the unloaded walk (a joint's speed, a gait
            constraint).
        walks: Whether the design walks the gait unloaded within its ratings.

    """

    mass: float
    limited_by: Cause
    walks: bool

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``mass`` [kg], ``limited_by`` (a cause's fields) and ``walks``."""
        return {"mass": self.mass, "limited_by": self.limited_by.to_dict(), "walks": self.walks}


def walking_payload_capacity(
    model: HexapodModel,
    gait: Gait | None = None,
    position: tuple[float, float, float] | None = None,
    gravity: float = GRAVITY,
) -> WalkingCapacity:
    """The largest payload at ``position`` the design carries walking ``gait``.

    Args:
        model: The design's Pinocchio model.
        gait: The gait (:class:`~hexaleg.gait.spec.Gait`'s defaults if omitted).
        position: Where the payload sits, body frame [m]; the centre of the body's top
            face if omitted.
        gravity: Gravitational acceleration g [m/s²].

    """
    gait = Gait() if gait is None else gait
    unloaded = Walker(model, gait, Payload(0.0, position), gravity=gravity)
    walk = unloaded.stride(gait.stride)
    if walk.violations:
        return WalkingCapacity(0.0, walk.violations[0].cause, False)
    rated_torques, rated_speeds = unloaded.rated()
    speeds = np.abs(walk.motion.velocity) / gait.period
    over = speeds > rated_speeds
    if over.any():
        return WalkingCapacity(0.0, _fastest(unloaded, over, speeds), False)
    loaded = Walker(model, gait, Payload(PROBE_MASS, position), gravity=gravity)
    loads = [w.loads(gait.stride, walk, gait.period) for w in (unloaded, loaded)]
    bounds = [
        _torque_bound(unloaded, loads, gait.period, rated_torques),
        _zmp_bound(unloaded, loads, walk.paths.position, gait),
    ]
    found = [b for b in bounds if b is not None]
    if any(mass < 0 for mass, _ in found):
        mass, cause = min(found, key=lambda b: b[0])
        return WalkingCapacity(0.0, cause, False)
    mass, cause = min(found, key=lambda b: b[0], default=(np.inf, Cause("search limit")))
    if mass > PAYLOAD_SEARCH_LIMIT:
        return WalkingCapacity(PAYLOAD_SEARCH_LIMIT, Cause("search limit"), True)
    return WalkingCapacity(float(mass), cause, True)


def _largest(offset: ArrayF, slope: ArrayF) -> tuple[float, int] | None:
    """The largest m ≥ 0 with every ``offset + m·slope ≥ 0`` (flat arrays), and which binds.

    Negative (with the index of the broken one) when one is broken at m = 0 already;
    ``None`` when none bounds m.
    """
    if (offset < 0).any():
        index = int(np.argmin(offset))
        return float(offset[index]), index
    shrinking = slope < 0
    if not shrinking.any():
        return None
    limits = np.full(offset.shape, np.inf)
    limits[shrinking] = -offset[shrinking] / slope[shrinking]
    index = int(np.argmin(limits))
    return float(limits[index]), index


def _torque_bound(
    walker: Walker, loads: list[Loads], period: float, rated: ArrayF
) -> tuple[float, Cause] | None:
    """Every joint within its rated torque: (−R ≤ τ₀ + m·Δτ ≤ R) at every sample."""
    base = loads[0].split.torques(period)  # (N, 6, 3)
    slope = (loads[1].split.torques(period) - base) / PROBE_MASS
    offset = np.concatenate(((rated - base).ravel(), (rated + base).ravel()))
    found = _largest(offset, np.concatenate(((-slope).ravel(), slope.ravel())))
    if found is None:
        return None
    mass, index = found
    _, leg, joint = np.unravel_index(index % base.size, base.shape)
    return mass, Cause("torque", walker.frames.legs[leg], LEG_JOINTS[joint])


def _zmp_bound(
    walker: Walker, loads: list[Loads], feet: ArrayF, gait: Gait
) -> tuple[float, Cause] | None:
    """The ZMP on the inner side of every edge of the standing feet's polygon."""
    period, height = gait.period, walker.frames.height
    wrenches = [load.rnea.static[:, :6] + load.rnea.inertial[:, :6] / period**2 for load in loads]
    travel = loads[0].rnea.configurations[:, :2]  # the body's footprint, ground frame
    # the ZMP's numerators: F_z·(x, y) relative to the body origin's footprint (stability.py)
    parts = []
    for wrench in wrenches:
        force, moment = wrench[:, :3], wrench[:, 3:]
        numerator = np.stack((-(moment[:, 1] + height * force[:, 0]),
                              moment[:, 0] - height * force[:, 1]), axis=-1)  # fmt: skip
        parts.append((numerator, force[:, 2]))
    stance = walker.phases.stance
    offsets, slopes = [], []
    for k in range(len(stance)):
        polygon = SupportPolygon.of_feet(feet[k, stance[k], :2] + travel[k])
        sides = []
        for numerator, vertical in parts:  # F_z·cross(edge, zmp − vertex) ≥ 0 inside
            relative = numerator[k] - (polygon.vertices - travel[k]) * vertical[k]
            edges = polygon.edges
            sides.append(edges[:, 0] * relative[:, 1] - edges[:, 1] * relative[:, 0])
        offsets.append(sides[0])
        slopes.append((sides[1] - sides[0]) / PROBE_MASS)
    found = _largest(np.concatenate(offsets), np.concatenate(slopes))
    return None if found is None else (found[0], Cause("zmp"))


def _fastest(walker: Walker, over: np.ndarray, speeds: ArrayF) -> Cause:
    """The fastest of the joints over their rated speed (N, 6, 3), as a cause."""
    index = np.unravel_index(int(np.argmax(np.where(over, speeds, -np.inf))), speeds.shape)
    return Cause("speed", walker.frames.legs[index[1]], LEG_JOINTS[index[2]])
