"""The front door: plan a gait (:func:`~hexaleg.gait.analyze_gait`), walk it in MuJoCo, measure.

:func:`simulate_gait` plans one period, refuses a gait the design cannot walk before
simulating anything (a stride beyond its max stride, or any constraint the planned
period breaks), then runs ``cycles`` periods from the period's first pose (:mod:`.run`)
with the planned joint trajectory and inverse-dynamics torques fed to the joints
(:mod:`.model`), measures the cycles after the first (:mod:`.measure`) and stands the
robot on a tripod beside the statics (:mod:`.standing`). A run that diverges stops
there, and the result says so instead of measuring it.

Two controllers follow the plan (:data:`~hexaleg._typing.Controller`), each the plan's
torques fed forward plus a PD on the tracking error, differing in its gains:

- ``servo``: stiff position servos, as hobby servos are
  (:data:`~.model.DEFAULT_BANDWIDTH`, critically damped), from rest. With three feet
  planted they also push the feet against each other, and drag a lifting foot still
  pressed into the floor: their torques exceed the plan's (the root's most);
- ``torque``: a torque-controlled robot, the PD's gains low (:data:`TORQUE_BANDWIDTH`,
  :data:`TORQUE_DAMPING_RATIO`), enough to hold the body's drift; it starts at the
  plan's velocities (its gains are too low to catch up from rest within a period).
"""

from __future__ import annotations

from hexaleg._checks import require_int
from hexaleg._typing import ArrayF, Controller, Distribution, require_choice
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
from hexaleg.sim.standing_tripod import StandingCheck, standing_check
from hexaleg.statics.forces import DEFAULT_FRICTION, Payload, check_friction
from hexaleg.statics.ground import Ground

TORQUE_BANDWIDTH = 0.5
"""The torque controller's PD bandwidth [Hz] on a standing leg's joints. Measured on the
default design: at 0.45 Hz the body drifts away within ten periods; above it the PD adds
more of its own (at 0.7 Hz the roots need 18 % more than the plan, at 1 Hz 64 %)."""
TORQUE_DAMPING_RATIO = 0.7
"""The torque controller's damping ratio [-]: more damping resists the lifting foot's
drag and adds to the roots' torques (ζ = 1: 11 % over the plan's at the roots)."""
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
    controller: Controller = "servo",
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
        gains: Joint servo gains (default: the controller's).
        model: The design's Pinocchio model, if already built, or an imported robot's.
        controller: ``"servo"`` (stiff position servos, from rest) or ``"torque"`` (the
            plan's torques, a low-gain PD, from the plan's velocities).

    Raises:
        ParameterError: ``stride`` beyond the design's max stride, or bad ``cycles``.
        HexalegError: The planned period breaks another constraint, or MuJoCo is missing.

    """
    require_mujoco()
    cycles = _checked_cycles(cycles, (Gait() if gait is None else gait).period, friction)
    model = HexapodModel(design) if model is None else model
    ground = Ground(friction=friction)  # level: MuJoCo's floor
    analysis = analyze_gait(design, gait, payload, distribution=distribution, ground=ground,
                            model=model, limits=False)  # fmt: skip
    require_walkable(analysis, model)
    gains = controller_gains(model, require_choice("controller", controller, Controller), gains)
    sim = SimModel(model, analysis.payload, friction, gains)
    plan, meter = plan_of(analysis), _meter(analysis.gait.period, analysis.base_velocity, model)
    run = run_plan(sim, plan, cycles * plan.period, FRAME_RATE, record=meter.add,
                   moving=controller == "torque")  # fmt: skip
    standing, diverged = _stand(sim, analysis.payload, friction, run.diverged)
    return SimulationResult(
        design=design, gait=analysis.gait, payload=analysis.payload, friction=friction,
        cycles=cycles, gains=sim.gains, metrics=None if diverged else meter.metrics(cycles),
        planned_peak_torque=dict(analysis.metrics.peak_torque), standing=standing,
        frames=run.frames, frame_torques=run.frame_torques, frame_rate=run.frame_rate,
        model=model, controller=controller, diverged=diverged,
    )  # fmt: skip


def _stand(
    sim: SimModel, payload: Payload, friction: float, walk_diverged: str
) -> tuple[StandingCheck | None, str]:
    """The tripod standing check after the walk, and where the simulation diverged if it did.

    A walk that diverged is not stood after; a stand that diverges has no check.
    """
    if walk_diverged:
        return None, f"while walking, {walk_diverged}"
    standing = standing_check(sim.hexapod, payload, friction, sim=sim)
    if standing.diverged:
        return None, f"while standing on {', '.join(standing.legs)}, {standing.diverged}"
    return standing, ""


def controller_gains(
    model: HexapodModel, controller: Controller, gains: ServoGains | None = None
) -> ServoGains:
    """``gains`` if given, else the controller's: a bandwidth on the model's joints."""
    if gains is not None:
        return gains
    if controller == "torque":
        return ServoGains.from_bandwidth(model, TORQUE_BANDWIDTH, TORQUE_DAMPING_RATIO)
    return ServoGains.from_bandwidth(model)


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
