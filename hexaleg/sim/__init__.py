"""Walking in a physics engine: the planned gait and the statics checked in MuJoCo.

:func:`simulate_gait` is the front door (:mod:`.simulate`). Beneath it: the MuJoCo
model of hexaleg's own URDF (:mod:`.model`), the planned period the servos follow
(:mod:`.plan`), the run that hands on every step as it goes (:mod:`.run`), what a walk shows
(:mod:`.measure`), the tripod standing check (:mod:`.standing_tripod`) and the offscreen video
(:mod:`.video`). MuJoCo is the optional extra ``hexaleg[sim]``, imported only when a
simulation runs.
"""

from hexaleg.sim.measure import Trace, WalkMeter, WalkMetrics, measure_walk
from hexaleg.sim.model import ServoGains, SimModel
from hexaleg.sim.plan import Plan
from hexaleg.sim.result import SimulationResult
from hexaleg.sim.run import Run, run_plan
from hexaleg.sim.simulate import plan_of, simulate_gait
from hexaleg.sim.standing_tripod import StandingCheck, standing_check
from hexaleg.sim.video import RenderOutcome, write_still, write_video

__all__ = [
    "Plan",
    "Run",
    "ServoGains",
    "SimModel",
    "SimulationResult",
    "StandingCheck",
    "Trace",
    "WalkMeter",
    "RenderOutcome",
    "WalkMetrics",
    "measure_walk",
    "plan_of",
    "run_plan",
    "simulate_gait",
    "standing_check",
    "write_still",
    "write_video",
]
