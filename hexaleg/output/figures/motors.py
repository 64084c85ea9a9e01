"""Motor figures of a gait period: where the electrical power goes, and each motor's envelope.

Drawn for the page as every figure of :mod:`hexaleg.output.figures`: per joint type, the
power its six motors draw against the phase, split into the shafts' mechanical power
τ_m·ω_m and the windings' copper loss i²R; and every sample's output speed and torque
over its actuator's envelope: the peak and continuous torques, the speed rating and the
voltage line, where the voltage the motor needs reaches the supply.
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from hexaleg._typing import ArrayF
from hexaleg.actuators import Actuator
from hexaleg.electrical.period import ElectricalResult
from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.figures.canvas import COLORS, drawn, new_figure, save

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


def voltage_line(actuator: Actuator, speeds: ArrayF, supply: float, resistance: float) -> ArrayF:
    """The largest motoring output torque the bus drives at each output speed [N·m].

    From |k_t·N·ω| + |i|·R = V with τ = N·η·k_t·i (motoring): τ = N·η·k_t·(V − k_t·N·ω)/R,
    V the bus voltage [V] and R the windings' resistance at their temperature [Ω]; infinite
    for R = 0 below the no-load speed, zero above it.
    """
    kt, ratio, eta = actuator.torque_constant, actuator.gear_ratio, actuator.gearbox_efficiency
    room = np.clip(supply - kt * ratio * np.abs(speeds), 0.0, None)
    if resistance == 0:
        return np.where(room > 0, np.inf, 0.0)
    torque: ArrayF = ratio * eta * kt * room / resistance
    return torque


def _resistance(analysis: GaitAnalysis, j: int) -> float:
    """Joint type ``j``'s winding resistance at the windings' temperature [Ω]."""
    actuators = analysis.design.actuators
    return float("nan") if actuators is None else actuators.resistances[j]


def _need(analysis: GaitAnalysis) -> tuple[ElectricalResult, tuple[Actuator, ...]]:
    electrical, actuators = analysis.electrical, analysis.design.actuators
    if electrical is None or actuators is None:
        raise ValueError("the design has no actuators: there are no motor figures")
    return electrical, actuators.joints


@drawn
def power_split_figure(analysis: GaitAnalysis) -> Figure:
    """Each joint type's motors' power against the phase: mechanical and copper loss."""
    electrical, actuators = _need(analysis)
    fig = new_figure(3.2)
    axes = fig.subplots(1, 3, sharey=True)
    phase = analysis.times / analysis.gait.period
    for j, (ax, joint) in enumerate(zip(axes, LEG_JOINTS, strict=True)):
        copper = (electrical.current[:, :, j] ** 2 * actuators[j].resistance).sum(axis=1)
        mechanical = electrical.electrical_power[:, :, j].sum(axis=1) - copper
        ax.fill_between(phase, 0.0, copper, color=COLORS[3], alpha=0.35, label="copper loss i²R")
        ax.plot(phase, mechanical, color=COLORS[0], lw=1.5, label="mechanical τ_m·ω_m")
        ax.plot(phase, mechanical + copper, color="k", lw=1.0, label="electrical P_e")
        ax.axhline(0.0, color="k", lw=0.5)
        drawn_power = np.maximum(mechanical + copper, 0.0).sum()  # what the supply gives
        share = 100 * copper.sum() / max(drawn_power, 1e-300)
        ax.set_title(f"{joint}\ncopper loss {share:.0f} % of P_e > 0")
        ax.set_xlabel("phase t/T [-]")
        ax.set_xlim(0, 1)
        ax.grid(True, alpha=0.3)
    axes[0].set_ylabel("six legs' motors [W]")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=3)
    total = electrical.copper_loss_per_period / max(electrical.energy_per_period, 1e-300)
    fig.suptitle(
        f"Power per joint type: {electrical.average_power:.4g} W on average, copper loss "
        f"{100 * total:.0f} % of the energy drawn"
    )
    return fig


@drawn
def envelope_figure(analysis: GaitAnalysis) -> Figure:
    """Every sample's |ω| and |τ| over its joint's actuator envelope, one colour per leg."""
    electrical, actuators = _need(analysis)
    fig = new_figure(3.4)
    axes = fig.subplots(1, 3)
    for j, (ax, joint) in enumerate(zip(axes, LEG_JOINTS, strict=True)):
        _envelope(ax, actuators[j], analysis, j)
        ax.set_title(f"{joint}: RMS {electrical.per_joint[joint].rms_torque:.3g} N·m")
        ax.set_xlabel("|q̇| [rad/s]")
    axes[0].set_ylabel("|τ| [N·m]")
    fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncols=5)
    fig.suptitle("Torque and speed at each sample over each motor's envelope")
    return fig


def _envelope(ax: Axes, actuator: Actuator, analysis: GaitAnalysis, j: int) -> None:
    speeds, torques = (
        np.abs(analysis.joint_velocities[:, :, j]),
        np.abs(analysis.joint_torques[:, :, j]),
    )
    top = 1.1 * max(actuator.rated_speed, actuator.no_load_speed, float(speeds.max()))
    grid = np.linspace(0.0, top, 200)
    bus = _need(analysis)[0].supply
    line = voltage_line(actuator, grid, bus, _resistance(analysis, j))
    limit = np.minimum(line, 2 * actuator.peak_torque)
    for i, leg in enumerate(analysis.legs):
        ax.scatter(
            speeds[:, i],
            torques[:, i],
            s=4,
            color=COLORS[i % len(COLORS)],
            label=leg if j == 0 else None,
        )
    ax.axhline(actuator.peak_torque, color="k", lw=1.2, label="peak torque")
    ax.axhline(actuator.continuous_torque, color="k", ls="--", lw=1.0, label="continuous torque")
    ax.axvline(actuator.rated_speed, color="k", ls=":", lw=1.0, label="speed rating")
    ax.plot(grid, limit, color=COLORS[3], lw=1.2, label=f"voltage line ({bus:g} V bus)")
    ax.set_xlim(0, top)
    ax.set_ylim(0, 1.15 * max(actuator.peak_torque, float(torques.max())))
    ax.grid(True, alpha=0.3)


def write_motor_figures(analysis: GaitAnalysis, out_dir: str | os.PathLike[str]) -> list[Path]:
    """Write ``gait_power.png`` and ``gait_envelope.png`` into ``out_dir`` (with actuators)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return [
        save(power_split_figure(analysis), out / "gait_power.png"),
        save(envelope_figure(analysis), out / "gait_envelope.png"),
    ]
