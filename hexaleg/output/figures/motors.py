"""Motor figures of a gait period: where the electrical power goes, and each motor's envelope.

Drawn for the page as every figure of :mod:`hexaleg.output.figures`: per joint type, the
power its six motors draw against the phase, split into the shafts' mechanical power
τ_m·ω_m and the windings' copper loss i²R; and every sample's output speed and torque
over its actuator's envelope: the peak and continuous torques, the speed rating and the
voltage line, where the voltage the motor needs reaches the supply.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
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


def voltage_speed(actuator: Actuator, torque: float, supply: float, resistance: float) -> float:
    """The output speed at which the bus drives at most ``torque`` motoring [rad/s].

    :func:`voltage_line` solved for the speed: ω = (V − τ·R/(N·η·k_t)) / (k_t·N), V the bus
    voltage [V] and R the windings' resistance at their temperature [Ω].
    """
    kt, ratio, eta = actuator.torque_constant, actuator.gear_ratio, actuator.gearbox_efficiency
    drop = torque * resistance / (ratio * eta * kt)
    return max(supply - drop, 0.0) / (kt * ratio)


def _bus(analysis: GaitAnalysis, j: int) -> tuple[float, float]:
    """The bus voltage [V] and joint type ``j``'s winding resistance at its temperature [Ω]."""
    electrical, actuators = _need(analysis), analysis.design.actuators
    resistance = float("nan") if actuators is None else actuators.resistances[j]
    return electrical[0].supply, resistance


def _need(analysis: GaitAnalysis) -> tuple[ElectricalResult, tuple[Actuator, ...]]:
    electrical, actuators = analysis.electrical, analysis.design.actuators
    if electrical is None or actuators is None:
        raise ValueError("the design has no actuators: there are no motor figures")
    return electrical, actuators.joints


@drawn
def power_split_figure(analysis: GaitAnalysis) -> Figure:
    """Each joint type's motors' power against the phase: mechanical and copper loss."""
    electrical, _ = _need(analysis)
    fig = new_figure(3.2)
    axes = fig.subplots(1, 3, sharey=True)
    phase = analysis.times / analysis.gait.period
    for j, (ax, joint) in enumerate(zip(axes, LEG_JOINTS, strict=True)):
        copper = (electrical.current[:, :, j] ** 2 * _bus(analysis, j)[1]).sum(axis=1)
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


NEAR = 1.5
"""A rating within this factor of the largest sample is drawn on the axes; one further out
would squeeze the samples into a corner, so the panel's title names it instead [-]."""


@drawn
def envelope_figure(analysis: GaitAnalysis) -> Figure:
    """Every sample's |ω| and |τ| over its joint's actuator envelope, one colour per leg.

    The axes fit the samples (and the ratings within :data:`NEAR` of them); a rating off
    the axes is named in its panel's title. A leg whose every sample lies under a later
    leg's (legs walking mirrored or shifted copies of one motion) is not in the legend:
    the legend names it with the legs drawn over it.
    """
    electrical, actuators = _need(analysis)
    offs = [_off_axes(actuators[j], analysis, j) for j in range(len(LEG_JOINTS))]
    notes = [f"{joint}: " + "; ".join(off) for joint, off in zip(LEG_JOINTS, offs, strict=True)
             if off]  # fmt: skip
    lines = len(notes) + 1 if notes else 0
    fig = new_figure(3.4 + 0.14 * lines)
    grid = fig.add_gridspec(2, 3, height_ratios=(2.6, 0.14 * lines + 1e-3))
    axes = [fig.add_subplot(grid[0, j]) for j in range(len(LEG_JOINTS))]
    shown: set[str] = set()
    for j, (ax, joint) in enumerate(zip(axes, LEG_JOINTS, strict=True)):
        _envelope(ax, actuators[j], analysis, j)
        shown |= _visible_legs(ax, analysis, j)
        ax.set_title(f"{joint}: RMS {electrical.per_joint[joint].rms_torque:.3g} N·m")
        ax.set_xlabel("|q̇| [rad/s]")
    axes[0].set_ylabel("|τ| [N·m]")
    text = fig.add_subplot(grid[1, :])
    text.axis("off")
    if notes:  # under the panels, above the legend
        note = text.text(0.0, 1.0, "\n".join(["Off the axes, far from every sample:", *notes]),
                         va="top", fontsize=7.5, transform=text.transAxes)  # fmt: skip
        note.set_in_layout(False)  # its row is sized for it: the panels keep their width
    handles, labels = _legend(axes, analysis, shown)
    fig.legend(handles, labels, loc="outside lower center", ncols=4, fontsize=7.5)
    fig.suptitle("Torque and speed at each sample over each motor's envelope")
    return fig


def _samples(analysis: GaitAnalysis, j: int) -> tuple[ArrayF, ArrayF]:
    """Every sample's |ω| and |τ| of joint ``j`` (samples, legs) [rad/s, N·m]."""
    return np.abs(analysis.joint_velocities[:, :, j]), np.abs(analysis.joint_torques[:, :, j])


def _reach(actuator: Actuator, analysis: GaitAnalysis, j: int) -> tuple[float, float]:
    """The axes' right and top: the samples and the ratings within :data:`NEAR`, +10 %."""
    speeds, torques = _samples(analysis, j)
    fastest, strongest = float(speeds.max()), float(torques.max())
    right = max([fastest, *(s for s in (actuator.rated_speed,) if s <= NEAR * fastest)])
    top = max([strongest, *(t for t, _, _ in _torques(actuator) if t <= NEAR * strongest)])
    return (1.1 * right or 1.0), (1.1 * top or 1.0)


def _torques(actuator: Actuator) -> list[tuple[float, str, str]]:
    """The actuator's torque ratings: value [N·m], name, line style."""
    return [
        (actuator.peak_torque, "peak torque", "-"),
        (actuator.continuous_torque, "continuous torque", "--"),
    ]


def _off_axes(actuator: Actuator, analysis: GaitAnalysis, j: int) -> list[str]:
    """The ratings of joint ``j``'s actuator that lie off its panel, in words."""
    right, top = _reach(actuator, analysis, j)
    off = [f"{what} {torque:.3g} N·m" for torque, what, _ in _torques(actuator) if torque > top]
    if actuator.rated_speed > right:
        off.append(f"speed rating {actuator.rated_speed:.3g} rad/s")
    past = voltage_speed(actuator, top, *_bus(analysis, j))
    if past > right:
        off.append(f"voltage line past {past:.3g} rad/s")
    return off


def _envelope(ax: Axes, actuator: Actuator, analysis: GaitAnalysis, j: int) -> None:
    """The samples, one colour per leg, and the ratings on the axes of :func:`_reach`."""
    speeds, torques = _samples(analysis, j)
    right, top = _reach(actuator, analysis, j)
    bus, resistance = _bus(analysis, j)
    for i, leg in enumerate(analysis.legs):
        ax.scatter(speeds[:, i], torques[:, i], s=4, color=COLORS[i % len(COLORS)],
                   label=leg)  # fmt: skip
    for torque, what, style in _torques(actuator):
        if torque <= top:
            ax.axhline(torque, color="k", ls=style, lw=1.1, label=what)
    if actuator.rated_speed <= right:
        ax.axvline(actuator.rated_speed, color="k", ls=":", lw=1.0, label="speed rating")
    if voltage_speed(actuator, top, bus, resistance) <= right:
        grid = np.linspace(0.0, right, 200)
        line = voltage_line(actuator, grid, bus, resistance)
        ax.plot(grid, np.minimum(line, 2 * top), color="k", ls="-.", lw=1.1,
                label=f"voltage line ({bus:g} V bus)")  # fmt: skip
    ax.set_xlim(0, right)
    ax.set_ylim(0, top)
    ax.grid(True, alpha=0.3)


def _visible_legs(ax: Axes, analysis: GaitAnalysis, j: int) -> set[str]:
    """The legs of which some sample is not under a later leg's marker on ``ax``.

    Measured in the axes' own units scaled to its drawn size: a sample is under another
    when their centres lie closer than :data:`COVER` of the axes' width or height.
    """
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    scale = np.array([1 / (x1 - x0), 1 / (y1 - y0)])
    points = [
        np.stack([np.abs(analysis.joint_velocities[:, i, j]),
                  np.abs(analysis.joint_torques[:, i, j])], axis=1) * scale
        for i in range(len(analysis.legs))
    ]  # fmt: skip
    visible = set()
    for i, leg in enumerate(analysis.legs):
        later = np.vstack(points[i + 1 :]) if i + 1 < len(points) else np.empty((0, 2))
        if not len(later) or (_nearest(points[i], later) > COVER).any():
            visible.add(leg)
    return visible


COVER = 0.006
"""Two samples closer than this share of the axes' size [-] draw as one marker (a 4 pt²
marker is 2 pt wide, 1 % of a 200 pt panel)."""


def _nearest(points: ArrayF, others: ArrayF) -> ArrayF:
    """Each point's distance to its nearest neighbour in ``others``."""
    from scipy.spatial import cKDTree

    distances, _ = cKDTree(others).query(points)
    return np.asarray(distances, dtype=float)


def _legend(axes: Sequence[Axes], analysis: GaitAnalysis, shown: set[str]) -> tuple[list, list]:
    """The legend: the legs drawn, one entry for the legs under them, then the ratings."""
    handles, labels = [], []
    for ax in axes:  # every rating drawn on some panel, once
        for handle, label in zip(*ax.get_legend_handles_labels(), strict=True):
            if label not in labels and (label in shown or label not in analysis.legs):
                handles.append(handle)
                labels.append(label)
    order = sorted(range(len(labels)), key=lambda k: labels[k] not in analysis.legs)
    handles, labels = [handles[k] for k in order], [labels[k] for k in order]
    hidden = [leg for leg in analysis.legs if leg not in shown]
    if hidden:
        from matplotlib.lines import Line2D

        handles.insert(len(shown), Line2D([], [], ls="none"))
        labels.insert(len(shown), f"{', '.join(hidden)}: under the others (same |q̇|, |τ|)")
    return handles, labels


def write_motor_figures(analysis: GaitAnalysis, out_dir: str | os.PathLike[str]) -> list[Path]:
    """Write ``gait_power.png`` and ``gait_envelope.png`` into ``out_dir`` (with actuators)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    return [
        save(power_split_figure(analysis), out / "gait_power.png"),
        save(envelope_figure(analysis), out / "gait_envelope.png"),
    ]
