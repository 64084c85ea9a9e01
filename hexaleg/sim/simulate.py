"""The front door: plan a gait (:func:`~hexaleg.gait.analyze_gait`), walk it in MuJoCo, measure.

:func:`simulate_gait` plans one period, refuses a gait the design cannot walk before
simulating anything (a stride beyond its max stride, or any constraint the planned
period breaks), then runs ``cycles`` periods from rest at the period's first pose
(:mod:`.run`) with the planned joint trajectory and inverse-dynamics torques fed to
the servos (:mod:`.model`), measures the cycles after the first (:mod:`.measure`) and
stands the robot on a tripod beside the statics (:mod:`.standing`).
"""

from __future__ import annotations

from hexaleg._checks import require_int
from hexaleg._typing import ArrayF, Distribution
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import ParameterError
from hexaleg.gait.analysis import GaitAnalysis, analyze_gait
from hexaleg.gait.spec import Gait
from hexaleg.gait.walkable import require_walkable
from hexaleg.robot.model import HexapodModel
from hexaleg.sim._mujoco import require_mujoco
from hexaleg.sim.measure import WalkMeter
from hexaleg.sim.model import ServoGains, SimModel
from hexaleg.sim.plan import Plan
from hexaleg.sim.result import SimulationResult
from hexaleg.sim.run import FRAME_RATE, MAX_DURATION, run_plan
from hexaleg.sim.standing_tripod import standing_check
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload, check_friction
from hexaleg.statics.ground import Ground

DEFAULT_CYCLES = 4
"""Gait periods simulated by default."""
CYCLES_RANGE = (2, 200)
"""Allowed number of periods: the first is not measured, so at least two."""


def plan_of(analysis: GaitAnalysis) -> Plan:
    """The planned period as the simulation follows it."""
    return Plan(
        period=analysis.gait.period,
        angles=analysis.joint_angles,
        rates=analysis.joint_velocities,
        torques=analysis.joint_torques,
        standing=analysis.stance,
        velocity=analysis.base_velocity[:2],
    )


def simulate_gait(
    design: HexapodDesign,
    gait: Gait | None = None,
    payload: Payload | None = None,
    *,
    cycles: int = DEFAULT_CYCLES,
    friction: float = DEFAULT_FRICTION,
    distribution: Distribution = "min-norm",
    gains: ServoGains | None = None,
    model: HexapodModel | None = None,
) -> SimulationResult:
    """Walk ``gait`` with ``design`` in MuJoCo for ``cycles`` periods; stand on a tripod.

    Args:
        design: The design.
        gait: The gait (:class:`~hexaleg.gait.spec.Gait`'s defaults if omitted).
        payload: A point mass on the body (none by default).
        cycles: Periods to simulate, 2 … 200; the first is not measured.
        friction: Coefficient of friction μ between feet and floor [-].
        distribution: How the plan shares the load among the standing feet
            (``"min-norm"`` or ``"min-torque"``, as in ``loads``): its feed-forward torques.
        gains: Joint servo gains (default: :meth:`ServoGains.from_bandwidth`).
        model: The design's Pinocchio model, if already built, or an imported robot's.

    Raises:
        ParameterError: ``stride`` beyond the design's max stride, or bad ``cycles``.
        HexalegError: The planned period breaks another constraint, or MuJoCo is missing.

    """
    require_mujoco()
    cycles = _checked_cycles(cycles, (Gait() if gait is None else gait).period, friction)
    model = HexapodModel(design) if model is None else model
    analysis = analyze_gait(
        design,
        gait,
        payload,
        distribution=distribution,
        ground=Ground(friction=friction),
        model=model,
        limits=False,
    )
    require_walkable(analysis, model)
    sim = SimModel(model, analysis.payload, friction, gains)
    plan, meter = plan_of(analysis), _meter(analysis.gait.period, analysis.base_velocity, model)
    run = run_plan(sim, plan, cycles * plan.period, FRAME_RATE, record=meter.add)
    return SimulationResult(
        design=design,
        gait=analysis.gait,
        payload=analysis.payload,
        friction=friction,
        cycles=cycles,
        gains=sim.gains,
        metrics=meter.metrics(cycles),
        planned_peak_torque=dict(analysis.metrics.peak_torque),
        standing=standing_check(model, analysis.payload, friction, sim=sim),
        frames=run.frames,
        frame_torques=run.frame_torques,
        frame_rate=run.frame_rate,
        robot=model if model.general_legs else None,
    )


def _checked_cycles(cycles: int, period: float, friction: float) -> int:
    """``cycles`` checked (no more periods than the longest simulation holds), ``friction`` too.

    The refusal names both the cycles and the period: either can be what is too long.
    """
    cycles = require_int("cycles", cycles, *CYCLES_RANGE)
    check_friction(friction)
    if cycles * period > MAX_DURATION:
        most = int(MAX_DURATION // period)
        fits = f"at most {most} at this period" if most >= CYCLES_RANGE[0] else "none fits"
        raise ParameterError(
            "cycles",
            cycles,
            f"cycles × period ({period:g} s, set by period or speed) must be at most "
            f"{MAX_DURATION:g} s simulated: {fits}",
        )
    return cycles


def _meter(period: float, velocity: ArrayF, model: HexapodModel) -> WalkMeter:
    """The walk's measures as it is simulated, each servo's peak held against its rating."""
    design = model.design
    return WalkMeter(
        period,
        velocity,
        float(model.nominal_base_pose().translation[2]),
        legs=model.leg_names,
        rated_torques=design.rated_torques,
    )
