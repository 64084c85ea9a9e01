"""The largest payload a design carries walking a gait, exactly: what binds, and at what mass.

A payload m at a fixed point of the body (default: the centre of its top face) changes
nothing in a gait period but the loads: the body moves parallel to the ground at constant
velocity, so the payload's weight is its only force, and the generalized forces of the
free-flyer model are affine in m: the base rows gain m times the closed-form wrench of
1 kg (:func:`~hexaleg.gait.dynamics.payload_wrench`: −g and its moment, g the walker's
gravity in the body frame, tilted on a slope). The minimum-norm foot forces are linear in
them, so every foot force and joint torque is affine in m as well, τ(m) = τ₀ + m·Δτ, and
so are the base wrench and, once multiplied by the normal force F_z(m) > 0, the
zero-moment point's side of every edge of the standing feet's polygon. One walk of the
gait (unloaded) and one min-norm solve with the wrench beside its own give τ₀, Δτ, the
forces' two parts and the wrench's, and every constraint becomes a bound on m:

- each joint at each sample: |τ₀ + m·Δτ| ≤ its rated torque;
- each edge of the support polygon at each sample: the ZMP on its inner side;
- each standing foot at each sample: its force within the friction cone,
  |f_t| ≤ μ·f_n, with f = f₀ + m·Δf: the end of an interval of m from 0, a root of a
  quadratic (:func:`~hexaleg.gait.friction.cone_limit`);
- with actuators (:mod:`hexaleg.actuators`), each leg's joint over the period: its RMS
  torque within the continuous torque C. The mean square over the samples is a quadratic
  in m, mean(τ₀²) + 2m·mean(τ₀·Δτ) + m²·mean(Δτ²) ≤ C², whose larger root is the bound;
- with actuators, each joint at each sample: the voltage its motor needs within the
  supply V (:mod:`hexaleg.electrical.equations`). At a sample's speed ω the voltage needed
  is the back-EMF |k_t·N·ω| plus R/k_t·|τ_m|, and τ_m is τ/(N·η) on the side of τ = 0
  where τ·ω ≥ 0 and τ·η/N on the other: piecewise affine in τ, one slope on each side of
  zero, so V bounds τ to a window [τ₋, τ₊] around zero, each end from its own branch, and
  τ₋ ≤ τ₀ + m·Δτ ≤ τ₊ bounds m exactly wherever τ changes sign along the way. The slopes
  are read off :func:`~hexaleg.electrical.equations.motor_samples` itself at ±the rated
  torque, so the capacity and the gait's electrical ratings share one set of equations;
- the joint speeds and the gait's own constraints (reach, joint limits, the ground) do not
  depend on m: broken unloaded, the design cannot walk the gait at all (capacity 0).

The actuators' masses and armatures are in the model both walks use, so they are in τ₀
and Δτ as they are in :func:`~hexaleg.gait.analysis.analyze_gait`. The capacity is the
smallest of those bounds (at most :data:`~hexaleg.statics.forces.PAYLOAD_SEARCH_LIMIT`),
and the constraint that gives it is what binds (of mirror-image legs that bind together, the
first in leg order, as the max speed and the standing capacity name them: round-off never
chooses); broken unloaded, the first broken in the order above (peak torque, ZMP, friction,
continuous torque, voltage) is what stops the walk.
On a slope (:class:`~hexaleg.statics.ground.Ground`) the walk has gravity tilted in the
body frame, and the payload's weight with it; a safety factor F divides the peak torque and
speed ratings (:meth:`~hexaleg.gait.walk.Walker.rated`). No search
and no bisection: the tests hold it against a bisection on
:func:`~hexaleg.gait.analysis.analyze_gait`, whose ``over_rating`` and ZMP margin first
report a broken rating just past the capacity.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg._typing import ArrayF, CauseKind
from hexaleg.actuators import Actuators
from hexaleg.cause import Cause
from hexaleg.electrical.equations import motor_samples
from hexaleg.exceptions import ParameterError
from hexaleg.gait.dynamics import CarriedLoad, GeneralizedForces, payload_wrench
from hexaleg.gait.friction import cone_limit
from hexaleg.gait.spec import Gait
from hexaleg.gait.stability import zmp_sides
from hexaleg.gait.walk import Loads, Stride, Walker
from hexaleg.gravity import GRAVITY
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.capacity import first_lowest_index
from hexaleg.statics.forces import PAYLOAD_SEARCH_LIMIT, Payload
from hexaleg.statics.ground import LEVEL, Ground

PROBE_MASS = 1.0
"""The payload whose wrench gives the change per kg [kg]: any positive mass gives the same maps."""


@dataclass(frozen=True)
class WalkingCapacity:
    """The largest payload walked within the ratings, and what binds.

    Attributes:
        mass: The payload [kg]; 0 when the design cannot walk the gait unloaded.
        limited_by: What binds at that payload (a joint's torque, the ZMP leaving the
            support polygon; with actuators, a joint's continuous torque or its motor's
            voltage), or what stops the unloaded walk (a joint's speed, a gait constraint).
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
    ground: Ground = LEVEL,
    safety_factor: float = 1.0,
) -> WalkingCapacity | None:
    """The largest payload at ``position`` the design carries walking ``gait``.

    ``None`` when the design gives no ratings (a robot file's efforts of 0): the capacity
    within them needs a rating.

    Args:
        model: The design's Pinocchio model.
        gait: The gait (:class:`~hexaleg.gait.spec.Gait`'s defaults if omitted).
        position: Where the payload sits, body frame [m]; the centre of the body's top
            face if omitted.
        gravity: Gravitational acceleration g [m/s²].
        ground: The ground walked on: its slope and friction (level by default).
        safety_factor: F ≥ 1 [-]: peak torques and joint speeds within rating / F.

    """
    if not model.design.rated:
        return None  # the capacity within the ratings needs them
    gait = Gait() if gait is None else gait
    unloaded = Walker(model, gait, Payload(0.0, position), ground=ground, gravity=gravity,
                      safety_factor=safety_factor)  # fmt: skip
    return walker_capacity(unloaded)


def walker_capacity(unloaded: Walker) -> WalkingCapacity:
    """:func:`walking_payload_capacity` of a walker already made, sharing its gait's walk.

    The walker's ground (its slope turns the payload's weight too, its friction holds the
    feet) and safety factor are the capacity's.

    Args:
        unloaded: The robot walking the gait without payload, the payload's point its
            position, min-norm forces.

    Raises:
        ParameterError: A walker with a payload, or another force distribution.

    """
    if unloaded.payload.mass != 0 or unloaded.distribution != "min-norm":
        raise ParameterError(
            "walker", unloaded.payload.mass, "carries no payload and splits min-norm forces"
        )
    model, gait = unloaded.model, unloaded.gait
    walk = unloaded.stride(gait.stride)
    if walk.violations:
        return WalkingCapacity(0.0, walk.violations[0].cause, False)
    rated_torques, rated_speeds = unloaded.rated()
    velocities = walk.motion.velocity / gait.period  # ω (N, 6, 3), whatever the payload
    speeds = np.abs(velocities)
    over = speeds > rated_speeds
    if over.any():
        return WalkingCapacity(0.0, _fastest(unloaded, over, speeds), False)
    probe = payload_wrench(unloaded.payload.point(model), PROBE_MASS, unloaded.gravity_vector)
    loads, carried = unloaded.own_loads_carrying(probe)
    base = loads.split.torques(gait.period)  # τ₀ (N, 6, 3)
    slope = carried.torques / PROBE_MASS  # Δτ
    legs = unloaded.frames.legs
    bounds = [
        _torque_bound(legs, base, slope, rated_torques),
        _zmp_bound(unloaded, walk, loads.rnea, probe),
        _grip_bound(unloaded, loads, carried),
    ]
    actuators, bus = model.design.actuators, model.design.bus_voltage
    if actuators is not None and bus is not None:
        bounds += [
            _continuous_bound(legs, base, slope, actuators),
            _voltage_bound(legs, base, slope, velocities, actuators, bus),
        ]
    found = [b for b in bounds if b is not None]
    broken = [b for b in found if b[0] < 0]
    if broken:
        return WalkingCapacity(0.0, broken[0][1], False)
    mass, cause = min(found, key=lambda b: b[0], default=(np.inf, Cause("search limit")))
    if mass > PAYLOAD_SEARCH_LIMIT:
        return WalkingCapacity(PAYLOAD_SEARCH_LIMIT, Cause("search limit"), True)
    return WalkingCapacity(float(mass), cause, True)


def _largest(offset: ArrayF, slope: ArrayF) -> tuple[float, int] | None:
    """The largest m ≥ 0 with every ``offset + m·slope ≥ 0``, and which binds (flat index).

    Negative (the most broken offset, with its index) when one is broken at m = 0
    already; ``None`` when none bounds m. Of bounds that tie (mirror-image legs) the first
    in the arrays' order binds (:func:`~hexaleg.statics.capacity.first_lowest_index`).
    """
    offset, slope = offset.ravel(), slope.ravel()
    if (offset < 0).any():
        return float(offset.min()), first_lowest_index(offset)
    shrinking = slope < 0
    if not shrinking.any():
        return None
    limits = np.full(offset.shape, np.inf)
    limits[shrinking] = -offset[shrinking] / slope[shrinking]
    return float(limits.min()), first_lowest_index(limits)


def _joint_cause(
    kind: CauseKind, legs: tuple[str, ...], index: int, shape: tuple[int, ...]
) -> Cause:
    """The cause of a bound on flat ``index`` into an array of ``shape`` (6, 3, ...)."""
    leg, joint, *_ = np.unravel_index(index, shape)
    return Cause(kind, legs[leg], LEG_JOINTS[joint])


def _window_bound(
    kind: CauseKind, legs: tuple[str, ...], base: ArrayF, slope: ArrayF, low: ArrayF, high: ArrayF
) -> tuple[float, Cause] | None:
    """Every joint at every sample with low ≤ τ₀ + m·Δτ ≤ high (each broadcast to (N, 6, 3)).

    Ties go in leg order, then joint order: the bounds are ordered (leg, joint, side, sample).
    """
    low, high = np.broadcast_to(low, base.shape), np.broadcast_to(high, base.shape)
    offset = np.stack((high - base, base - low)).transpose(_LEG_FIRST)
    found = _largest(offset, np.stack((-slope, slope)).transpose(_LEG_FIRST))
    if found is None:
        return None
    mass, index = found
    return mass, _joint_cause(kind, legs, index, offset.shape)


_LEG_FIRST = (2, 3, 0, 1)
"""(side, sample, leg, joint) → (leg, joint, side, sample)."""


def _torque_bound(
    legs: tuple[str, ...], base: ArrayF, slope: ArrayF, rated: ArrayF
) -> tuple[float, Cause] | None:
    """Every joint within its rated torque: (−R ≤ τ₀ + m·Δτ ≤ R) at every sample."""
    return _window_bound("torque", legs, base, slope, -rated, rated)


def _continuous_bound(
    legs: tuple[str, ...], base: ArrayF, slope: ArrayF, actuators: Actuators
) -> tuple[float, Cause] | None:
    """Each leg's joint's RMS torque within its continuous torque C: a quadratic in m.

    mean((τ₀ + m·Δτ)²) ≤ C² is A·m² + 2B·m − D ≤ 0 with A = mean(Δτ²), B = mean(τ₀·Δτ)
    and D = C² − mean(τ₀²), convex in m: the bound is its larger root (−B + √(B² + A·D))/A,
    written D/(B + √(B² + A·D)) when B ≥ 0, lest it cancel. Negative D: broken unloaded.
    """
    quadratic, linear = np.mean(slope**2, axis=0), np.mean(base * slope, axis=0)  # (6, 3)
    headroom = np.square(actuators.continuous_torques) - np.mean(base**2, axis=0)
    if (headroom < 0).any():
        index = first_lowest_index(headroom)
        return float(headroom.min()), _joint_cause("continuous_torque", legs, index, headroom.shape)
    grows = quadratic > 0  # else Δτ = 0 throughout: the RMS does not change with m
    if not grows.any():
        return None
    root = np.sqrt(linear**2 + quadratic * headroom)
    limits = np.full(headroom.shape, np.inf)
    ahead = grows & (linear >= 0)
    limits[ahead] = headroom[ahead] / (linear[ahead] + root[ahead])
    behind = grows & (linear < 0)
    limits[behind] = (root[behind] - linear[behind]) / quadratic[behind]
    index = first_lowest_index(limits)
    return float(limits.min()), _joint_cause("continuous_torque", legs, index, limits.shape)


def _voltage_bound(
    legs: tuple[str, ...],
    base: ArrayF,
    slope: ArrayF,
    speeds: ArrayF,
    actuators: Actuators,
    supply: float,
) -> tuple[float, Cause] | None:
    """Each joint's motor at every sample within the bus voltage V: a window around τ = 0.

    The voltage needed at speed ω is e + s₊·τ for τ ≥ 0 and e − s₋·τ for τ < 0 (e the
    back-EMF; s₊, s₋ ≥ 0 the two branches' volts per N·m), read off the motor equations at
    τ = 0 and ±P (P the rated torque). V then bounds τ to [−(V − e)/s₋, (V − e)/s₊]; a
    branch with no slope (R = 0) bounds nothing while e ≤ V and everything once e > V.
    """
    probe = np.broadcast_to(np.asarray(actuators.rated_torques), base.shape)
    emf, up, down = (
        motor_samples(torque, speeds, actuators).voltage
        for torque in (np.zeros_like(probe), probe, -probe)
    )
    headroom = supply - emf
    return _window_bound(
        "voltage",
        legs,
        base,
        slope,
        -_reach(headroom, (down - emf) / probe),
        _reach(headroom, (up - emf) / probe),
    )


def _reach(headroom: ArrayF, volts_per_torque: ArrayF) -> ArrayF:
    """How far τ may go from zero on one branch: headroom / slope (±inf without a slope)."""
    unbounded = np.where(headroom >= 0, np.inf, -np.inf)
    sloped = volts_per_torque > 0
    reach: ArrayF = np.where(sloped, headroom / np.where(sloped, volts_per_torque, 1.0), unbounded)
    return reach


def _zmp_bound(
    walker: Walker, walk: Stride, rnea: GeneralizedForces, probe: ArrayF
) -> tuple[float, Cause] | None:
    """The ZMP on the inner side of every edge of the standing feet's polygon.

    Each side (:func:`~hexaleg.gait.stability.zmp_sides`) is linear in the base's wrench,
    which is affine in the payload: the unloaded walk's sides at its period (from their
    static and inertial parts, :meth:`~hexaleg.gait.walk.Walker.zmp_sides`, the max
    speed's too) and their change per kg (``probe``: the wrench of :data:`PROBE_MASS` on
    the base rows, under the walker's gravity: on a slope its weight pushes along the
    plane too).
    """
    static, inertial = walker.zmp_sides(walk, rnea)
    configurations = rnea.configurations  # the body's path, as the payload's
    change = zmp_sides(
        np.broadcast_to(probe / PROBE_MASS, (len(configurations), 6)),
        walker.frames.height,
        configurations[:, :2],
        walker.supports(walk, configurations),
    )
    base = static + inertial / walker.gait.period**2
    found = _largest(base, change)
    return None if found is None else (found[0], Cause("zmp"))


def _grip_bound(walker: Walker, loads: Loads, carried: CarriedLoad) -> tuple[float, Cause] | None:
    """Every standing foot's force within the friction cone, |f_t| ≤ μ·f_n (affine in m).

    The feet's forces are the unloaded walk's plus m times what :data:`PROBE_MASS`
    adds per kg (``carried``: its min-norm share, split with the walk's).
    """
    base = loads.split.forces(walker.gait.period)
    slope = carried.forces / PROBE_MASS
    found = cone_limit(base, slope, walker.phases.stance, walker.ground.friction)
    if found is None:
        return None
    mass, index = found
    leg = index % len(walker.frames.legs)
    return mass, Cause("slide", walker.frames.legs[leg])


def _fastest(walker: Walker, over: np.ndarray, speeds: ArrayF) -> Cause:
    """The fastest of the joints over their rated speed (N, 6, 3), as a cause (ties: leg order)."""
    fastest = np.where(over, -speeds, np.inf).transpose(1, 2, 0)  # (leg, joint, sample)
    return _joint_cause("speed", walker.frames.legs, first_lowest_index(fastest), fastest.shape)
