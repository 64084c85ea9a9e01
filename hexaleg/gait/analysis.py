"""The front door of walking: :func:`analyze_gait` gives one design's gait period, measured.

It walks the gait (:class:`~hexaleg.gait.walk.Walker`): foot paths and joint motion
(:mod:`.trajectory`), constraints (:mod:`.feasibility`), inverse dynamics and the feet's
forces (:mod:`.dynamics`), the ZMP (:mod:`.stability`) and the metrics (:mod:`.metrics`),
then the max stride and max speed (:mod:`.limits`). The result keeps every time series a
simulator or an optimizer needs: the joint trajectories (q, q̇, q̈), the planned
torques and the feet's forces at each sample.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
import numpy.typing as npt

from hexaleg._typing import ArrayF, Distribution
from hexaleg.cause import Cause
from hexaleg.design import HexapodDesign
from hexaleg.electrical.period import ElectricalResult, analyze_electrical
from hexaleg.gait.feasibility import TOLERANCE, Violation
from hexaleg.gait.friction import Slip, friction_ratios, slips
from hexaleg.gait.limits import SpeedLimit, StrideLimit, max_speed, max_stride
from hexaleg.gait.metrics import GaitMetrics, gait_metrics
from hexaleg.gait.spec import Gait
from hexaleg.gait.stability import Supports, zero_moment_points, zmp_margins
from hexaleg.gait.trajectory import LegFrames
from hexaleg.gait.walk import Loads, Stride, Walker
from hexaleg.gravity import GRAVITY
from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.forces import Payload
from hexaleg.statics.ground import LEVEL, Ground
from hexaleg.statics.ratings import OverRating, at_times, over_rating
from hexaleg.structure.check import StructureCheck
from hexaleg.structure.walking import check_walking
from hexaleg.swing.workspace import standing_reach


@dataclass(frozen=True)
class GaitAnalysis:
    """One design walking one gait period: time series, metrics, feasibility and limits.

    Arrays are per sample (N, at t_k = k·T/N) and per leg (6, ``legs`` order).

    Attributes:
        design: The design.
        gait: The gait.
        payload: The payload carried.
        distribution: How the standing feet share the load.
        ground: The ground walked on (its slope turns gravity in the body frame; its
            friction holds the standing feet).
        safety_factor: F [-]: peak torques and joint speeds are held within rating / F.
        mass: Total mass, payload included [kg].
        legs: Leg names.
        frames: The legs' roots and nominal footholds in the body frame (from the model).
        times: t_k (N,) [s].
        stance: Whether each foot stands (N, 6).
        joint_angles: q (N, 6, 3) [rad], (root, hip, knee) per leg.
        joint_velocities: q̇ (N, 6, 3) [rad/s].
        joint_accelerations: q̈ (N, 6, 3) [rad/s²].
        configurations: Pinocchio's q of the free-flyer model (N, nq) [m, -, rad]: the
            body's position (world frame, the ground at z = 0), its orientation
            (identity: it never rotates) and the joints.
        generalized_velocities: Pinocchio's v (N, nv) [m/s, rad/s] (the body's in its
            own frame, which stays level).
        generalized_accelerations: Pinocchio's a (N, nv) [m/s², rad/s²].
        base_velocity: The body's constant velocity v·u, world frame (3,) [m/s].
        joint_torques: τ (N, 6, 3) [N·m].
        foot_forces: Each foot's force from the ground (N, 6, 3), ground frame [N]
            (zero while it swings).
        feet: Foot positions (N, 6, 3) in the body frame [m].
        zmp: The zero-moment point (N, 2) [m], ground frame, on the ground's plane (its
            margin: :attr:`zmp_margin`, computed on first use).
        supports: The standing feet's support polygons along the period, ground frame.
        metrics: Peaks, RMS, positive work, cost of transport.
        violations: Every constraint the period breaks, earliest first (none: feasible).
        max_stride: The largest feasible stride (None if not computed).
        max_speed: The fastest walk within the ratings (None if not computed, or if the
            design gives no ratings: it needs one).
        electrical: The period's currents, voltages, energy and battery use, and each
            joint against its actuator's ratings (None for a design without actuators).
        structure: The legs' tubes at every sample (None without a ``[structure]``).

    """

    design: HexapodDesign
    gait: Gait
    payload: Payload
    distribution: Distribution
    ground: Ground
    safety_factor: float
    mass: float
    legs: tuple[str, ...]
    frames: LegFrames
    times: ArrayF
    stance: npt.NDArray[np.bool_]
    joint_angles: ArrayF
    joint_velocities: ArrayF
    joint_accelerations: ArrayF
    configurations: ArrayF
    generalized_velocities: ArrayF
    generalized_accelerations: ArrayF
    base_velocity: ArrayF
    joint_torques: ArrayF
    foot_forces: ArrayF
    feet: ArrayF
    zmp: ArrayF
    supports: Supports
    metrics: GaitMetrics
    violations: tuple[Violation, ...]
    max_stride: StrideLimit | None
    max_speed: SpeedLimit | None
    electrical: ElectricalResult | None
    structure: StructureCheck | None = None

    @cached_property
    def zmp_margin(self) -> ArrayF:
        """The ZMP's signed distance inside the standing feet's polygon (N,) [m]."""
        return zmp_margins(self.zmp, self.supports)

    @property
    def min_zmp_margin(self) -> float:
        """The smallest ZMP margin over the period [m] (positive: inside throughout)."""
        return float(self.zmp_margin.min())

    @property
    def walkable(self) -> bool:
        """Whether the period breaks no constraint of its motion (joint limits, reach…)."""
        return not self.violations

    @cached_property
    def tipping(self) -> Violation | None:
        """When the ZMP first leaves the standing feet's polygon (None: it never does).

        Past it the feet would have to pull on the ground: the robot tips over.
        """
        outside = np.flatnonzero(self.zmp_margin < -TOLERANCE)
        return None if not outside.size else Violation(float(self.times[outside[0]]), Cause("zmp"))

    @cached_property
    def friction_ratios(self) -> ArrayF:
        """|f_t| / f_n of each standing foot's planned force (N, 6) [-] (0 swinging)."""
        return friction_ratios(self.foot_forces, self.stance)

    @property
    def friction_needed(self) -> float:
        """The least friction coefficient μ every standing foot's force needs [-].

        Infinite (``null`` in JSON) when the plan makes a standing foot pull on the ground.
        """
        return float(self.friction_ratios.max())

    @cached_property
    def slips(self) -> tuple[Slip, ...]:
        """Each foot whose planned force leaves the friction cone, at its worst (leg order)."""
        return slips(self.friction_ratios, self.times, self.legs, self.ground.friction)

    @property
    def feasible(self) -> bool:
        """Whether the period can be walked as planned: every constraint, rating and tube.

        Walkable: no constraint of its motion breaks (:attr:`violations`); upright: its
        ZMP never leaves the standing feet's polygon (:attr:`tipping`); gripping: no
        standing foot's force leaves the friction cone (:attr:`slips`); strong: no leg tube
        over its strength (:attr:`structure`); within every rating (:attr:`over_rating`):
        peak torque and joint speed within rating / F and, with actuators, RMS torque and
        the voltage the motors need. The max speed is then at least the speed walked.
        """
        return self.infeasible_because is None

    @property
    def infeasible_because(self) -> str | None:
        """What makes the period infeasible, in one line (None: it is feasible).

        The first broken constraint of the motion, else the ZMP leaving the polygon (with
        the smallest margin), else a foot sliding, else the joints over their ratings.
        """
        if self.violations:
            return str(self.violations[0])
        if self.tipping is not None:
            return f"{self.tipping} (min ZMP margin {self.min_zmp_margin:.4g} m)"
        if self.slips:
            more = f" (and {len(self.slips) - 1} more feet)" if len(self.slips) > 1 else ""
            return f"{self.slips[0]}{more}"
        if self.structure is not None and self.structure.worst_ratio > 1:
            return "a leg segment over its strength (below)"
        over = self.over_rating
        if over:
            more = f" (and {len(over) - 1} more, below)" if len(over) > 1 else ""
            return f"over its ratings: {over[0]}{more}"
        return None

    @property
    def over_rating(self) -> tuple[OverRating, ...]:
        """Each joint over a rating, with when it peaks.

        With actuators: peak torque and speed (within rating / F), continuous (RMS) torque
        and voltage; without, the peak |τ| and |q̇| against the rated torque and speed / F.
        """
        if self.electrical is not None:
            return self.electrical.over_rating
        places = at_times(self.times)
        design, factor = self.design, self.safety_factor
        return over_rating(
            self.legs, self.joint_torques, design.rated_torques, places, "torque", factor
        ) + over_rating(
            self.legs, self.joint_velocities, design.rated_speeds, places, "speed", factor
        )

    @property
    def unchecked_ratings(self) -> tuple[str, ...]:
        """The ratings the design does not give, so :attr:`feasible` could not check them.

        ``"torque"``, ``"speed"`` or both (a robot file's ``effort="0"``); none with
        actuators, whose tables give both.
        """
        if self.electrical is not None:
            return ()
        design = self.design
        given = {"torque": design.rated_torques, "speed": design.rated_speeds}
        return tuple(kind for kind, rating in given.items() if rating is None)

    def time_series(self) -> dict[str, ArrayF]:
        """The time series as named columns (N,) each.

        ``t`` [s]; per leg and joint ``<leg>_<joint>_q`` [rad], ``_qd`` [rad/s], ``_qdd``
        [rad/s²], ``_tau`` [N·m]; per leg ``<leg>_stance`` (1 standing, 0 swinging) and
        its foot's force ``<leg>_fx``, ``_fy``, ``_fz`` [N], ground frame; with actuators,
        per leg and joint ``_current`` [A], ``_voltage`` (needed) [V] and ``_power`` (P_e) [W].
        """
        columns = {"t": self.times}
        for i, leg in enumerate(self.legs):
            for j, joint in enumerate(LEG_JOINTS):
                for suffix, values in (
                    ("q", self.joint_angles),
                    ("qd", self.joint_velocities),
                    ("qdd", self.joint_accelerations),
                    ("tau", self.joint_torques),
                ):
                    columns[f"{leg}_{joint}_{suffix}"] = values[:, i, j]
            columns[f"{leg}_stance"] = self.stance[:, i].astype(float)
            for axis, k in (("x", 0), ("y", 1), ("z", 2)):
                columns[f"{leg}_f{axis}"] = self.foot_forces[:, i, k]
        return columns | ({} if self.electrical is None else self.electrical.time_series())

    def reach_clouds(self, model: HexapodModel) -> dict[str, ArrayF]:
        """Each leg's reach while standing, body frame (K, 3) [m]: a Monte Carlo cloud.

        Each leg by its own leg within the limits that hold it standing
        (:func:`~hexaleg.swing.workspace.standing_reach`), ``model`` this period's robot.
        """
        clouds = standing_reach(model)
        return {
            leg: self.frames.points_in_body(clouds[leg].points)[i]
            for i, leg in enumerate(self.legs)
        }

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI: s, m, kg, N·m, rad/s, W, J); the time series are left out."""
        return {
            "design": self.design.as_dict(),
            "gait": self.gait.to_dict(),
            "payload": self.payload.to_dict(self.design),
            "distribution": self.distribution,
            "ground": self.ground.to_dict(self.gait.heading),
            "safety_factor": self.safety_factor,
            "mass": self.mass,
            **self.metrics.to_dict(),
            "min_zmp_margin": self.min_zmp_margin,
            "friction_needed": _finite(self.friction_needed),
            "slips": [slip.to_dict() for slip in self.slips],
            "feasible": self.feasible,
            "infeasible_because": self.infeasible_because,
            "ratings_not_checked": list(self.unchecked_ratings),
            "violations": [v.to_dict() for v in self.violations],
            "tipping": None if self.tipping is None else self.tipping.to_dict(),
            "max_stride": None if self.max_stride is None else self.max_stride.value,
            "max_speed": None if self.max_speed is None else self.max_speed.to_dict(),
            "over_rating": [o.to_dict() for o in self.over_rating],
            **_electrical_dict(self.electrical),
            "structure": None if self.structure is None else self.structure.to_dict(),
            "units": {
                "period, time": "s",
                "stride, step_height, max_stride, min_zmp_margin, position": "m",
                "heading, slope": "rad",
                "slope_deg": "°",
                "friction, friction_needed, safety_factor": "1",
                "speed, max_speed": "m/s",
                "mass": "kg",
                "peak_torque, rms_torque": "N·m",
                "peak_speed": "rad/s",
                "peak_power": "W",
                "positive_work": "J",
                "mechanical_cost_of_transport, duty_factor": "1",
                "electrical": "J, W, Wh/km; per joint N·m, A, V, J; cost_of_transport 1",
                "battery": "kg, Wh, h, km",
            },
        }


def _finite(value: float) -> float | None:
    """``value``, or ``None`` (JSON's null) where it is unbounded."""
    return value if math.isfinite(value) else None


def _electrical_dict(electrical: ElectricalResult | None) -> dict[str, Any]:
    """``electrical`` and ``battery`` of the JSON (``None`` each without actuators)."""
    if electrical is None:
        return {"electrical": None, "battery": None}
    return electrical.to_dict()


def analyze_gait(
    design: HexapodDesign,
    gait: Gait | None = None,
    payload: Payload | None = None,
    *,
    distribution: Distribution = "min-norm",
    ground: Ground = LEVEL,
    model: HexapodModel | None = None,
    limits: bool = True,
    speed: bool = False,
    gravity: float = GRAVITY,
    safety_factor: float = 1.0,
) -> GaitAnalysis:
    """One gait period of ``design``: time series, metrics, feasibility, max stride and speed.

    Args:
        design: The design.
        gait: The gait (:class:`~hexaleg.gait.spec.Gait`'s defaults if omitted).
        payload: A point mass on the body (none by default).
        distribution: ``"min-norm"`` (default) or ``"min-torque"`` forces.
        ground: The ground walked on (:class:`~hexaleg.statics.ground.Ground`): its slope
            and friction μ (level, the default μ, if omitted).
        model: The design's Pinocchio model, if already built.
        limits: Also compute the max stride and max speed (the slower part).
        speed: Without ``limits``, still compute the max speed, at the gait's stride only
            (zero if it is infeasible): with min-norm forces that needs no search and no
            more inverse dynamics.
        gravity: Gravitational acceleration g [m/s²].
        safety_factor: F ≥ 1 [-]: peak torques and joint speeds within rating / F (the
            feasibility, the flags, the max stride and the max speed).

    """
    gait = Gait() if gait is None else gait
    model = HexapodModel(design) if model is None else model
    walker = Walker(model, gait, payload, distribution, ground, gravity, safety_factor)
    return analyze_walker(walker, limits=limits, speed=speed)


def analyze_walker(walker: Walker, *, limits: bool = True, speed: bool = False) -> GaitAnalysis:
    """:func:`analyze_gait` of a walker already made (its gait's walk shared with others).

    The walker's ground, payload, split and safety factor are the analysis's; ``limits``
    and ``speed`` are :func:`analyze_gait`'s.
    """
    gait, distribution = walker.gait, walker.distribution
    walk = walker.stride(gait.stride)
    loads = walker.loads(gait.stride, walk, gait.period)
    known = (walk, loads) if distribution == "min-norm" else None
    stride_limit = max_stride(walker) if limits else None
    speed_limit = (
        max_speed(walker, stride_limit, known, fallback=limits)
        if (limits or speed) and walker.model.design.rated
        else None  # no ratings: the max speed needs one
    )
    return _analysis(walker, walk, loads, stride_limit, speed_limit)


def _analysis(
    walker: Walker,
    walk: Stride,
    loads: Loads,
    stride_limit: StrideLimit | None,
    speed_limit: SpeedLimit | None,
) -> GaitAnalysis:
    """The result of a walk: its time series at the gait's period, metrics and limits."""
    gait, period, rnea = walker.gait, walker.gait.period, loads.rnea
    torques, velocities = loads.split.torques(period), walk.motion.velocity / period
    times, forces = walker.times(period), loads.split.forces(period)
    rates, accelerations = rnea.velocities / period, rnea.accelerations / period**2
    wrench = rnea.static[:, :6] + rnea.inertial[:, :6] / period**2
    travel = rnea.configurations[:, :2]  # the body's origin over the ground
    weight_travel = walker.robot.mass * walker.gravity * gait.stride / walker.phases.duty_factor
    return GaitAnalysis(
        design=walker.model.design,
        gait=gait,
        payload=walker.payload,
        distribution=walker.distribution,
        ground=walker.ground,
        safety_factor=walker.safety_factor,
        mass=walker.robot.mass,
        legs=walker.frames.legs,
        frames=walker.frames,
        times=times,
        stance=walker.phases.stance,
        joint_angles=walk.motion.angles,
        joint_velocities=velocities,
        joint_accelerations=walk.motion.acceleration / period**2,
        configurations=rnea.configurations,
        generalized_velocities=rates,
        generalized_accelerations=accelerations,
        base_velocity=gait.speed * walker.heading,
        joint_torques=torques,
        foot_forces=forces,
        feet=walk.paths.position,
        zmp=zero_moment_points(wrench, walker.frames.height) + travel,
        supports=walker.supports(walk, rnea.configurations),
        metrics=gait_metrics(torques, velocities, period, weight_travel),
        violations=walk.violations,
        max_stride=stride_limit,
        max_speed=speed_limit,
        electrical=_electrical(walker, torques, velocities),
        structure=check_walking(
            walker.model,
            times,
            rnea.configurations,
            rates,
            accelerations,
            forces,
            walker.gravity_vector,
        ),
    )


def _electrical(walker: Walker, torques: ArrayF, velocities: ArrayF) -> ElectricalResult | None:
    """The period through the design's motors (:mod:`hexaleg.electrical`), if it has them."""
    design, gait = walker.model.design, walker.gait
    if design.actuators is None:
        return None
    return analyze_electrical(
        torques,
        velocities,
        gait.period,
        gait.speed,
        walker.robot.mass,
        walker.gravity,
        design.actuators,
        design.battery,
        walker.frames.legs,
        design.bus_voltage,
        walker.safety_factor,
    )


STUDY_GAIT = Gait()
"""The gait every design of a study walks: :class:`Gait`'s defaults."""
