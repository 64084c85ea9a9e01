"""Synthetic hexapod URDFs drawn at random, written as text, for the import tests.

Each leg is drawn in its leg-root frame from known dimensions (coxa a1, hip height h,
femur l2, tibia l3, lateral offset e), then written the way real descriptions are:
every joint axis on z with the frame turned by rpy, left legs mirrored by a roll of π
(their yaw axis pointing down), segments bent from their joint-to-joint lines, fixed
joints inside a leg, a collision mesh at scale 0.001, random masses and inertias.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pinocchio as pin


@dataclass(frozen=True)
class DrawnLeg:
    """The dimensions a synthetic leg was drawn from [m]."""

    coxa: float
    hip_height: float
    femur: float
    tibia: float
    lateral: float
    mount: np.ndarray


def _rz(a: float) -> np.ndarray:
    return pin.utils.rotate("z", a)


def _ry(a: float) -> np.ndarray:
    return pin.utils.rotate("y", a)


def _rx(a: float) -> np.ndarray:
    return pin.utils.rotate("x", a)


def _frame(rotation: np.ndarray, origin) -> np.ndarray:
    m = np.eye(4)
    m[:3, :3] = rotation
    m[:3, 3] = origin
    return m


def _origin(parent: np.ndarray, child: np.ndarray) -> str:
    rel = np.linalg.inv(parent) @ child
    xyz = " ".join(repr(float(v)) for v in rel[:3, 3])
    rpy = " ".join(repr(float(v)) for v in pin.rpy.matrixToRpy(rel[:3, :3]))
    return f'<origin xyz="{xyz}" rpy="{rpy}"/>'


def _inertial(rng: np.random.Generator) -> str:
    mass = float(rng.uniform(0.02, 0.5))
    moments = rng.uniform(1e-5, 1e-3, 3)
    moments[2] = rng.uniform(abs(moments[0] - moments[1]), moments[0] + moments[1])
    turn = pin.rpy.rpyToMatrix(*rng.uniform(-np.pi, np.pi, 3))
    i = (turn @ np.diag(moments) @ turn.T).tolist()
    com = " ".join(repr(float(v)) for v in rng.uniform(-0.03, 0.03, 3))
    return (
        f'<inertial><origin xyz="{com}" rpy="0 0 0"/><mass value="{mass!r}"/>'
        f'<inertia ixx="{i[0][0]!r}" ixy="{i[0][1]!r}" ixz="{i[0][2]!r}" iyy="{i[1][1]!r}" '
        f'iyz="{i[1][2]!r}" izz="{i[2][2]!r}"/></inertial>'
    )


class _Writer:
    def __init__(self, rng: np.random.Generator) -> None:
        self.rng = rng
        self.parts: list[str] = []
        self.frames: dict[str, np.ndarray] = {}
        self.bound = 2.5  # every joint's |q| limit [rad]

    def link(self, name: str, frame: np.ndarray, extra: str = "") -> None:
        self.frames[name] = frame
        self.parts.append(f'<link name="{name}">{_inertial(self.rng)}{extra}</link>')

    def joint(
        self, name: str, kind: str, parent: str, child: str, frame: np.ndarray, axis: str = "0 0 1"
    ) -> None:
        limit = f'<limit lower="{-self.bound}" upper="{self.bound}" effort="3.1" velocity="5.2"/>'
        self.parts.append(
            f'<joint name="{name}" type="{kind}"><parent link="{parent}"/><child link="{child}"/>'
            f"{_origin(self.frames[parent], frame)}"
            + (f'<axis xyz="{axis}"/>{limit}' if kind != "fixed" else "")
            + "</joint>"
        )
        self.link(child, frame)


def _pitch_frame(rng: np.random.Generator, point) -> tuple[np.ndarray, str]:
    """A pitch joint's frame (its axis on z or −z, turned by rpy onto ±y) at ``point``."""
    along = rng.choice([1.0, -1.0])
    turn = _ry(rng.uniform(-np.pi, np.pi)) @ _rx(-along * np.pi / 2)  # z → along·y
    axis = rng.choice(["0 0 1", "0 0 -1"])
    return _frame(turn, point), axis


def draw_hexapod(
    seed: int, foot_link: bool = True, same_legs: bool = False
) -> tuple[str, list[DrawnLeg]]:
    """URDF text of a random hexapod and the dimensions each leg was drawn from.

    With ``same_legs``, every leg has the first one's dimensions and bends, and every
    mount lies in one plane (a robot that stands level), each still written in its own
    frames (rpy turns, mirroring, fixed links drawn anew).
    """
    first = None
    rng = np.random.default_rng(seed)
    w = _Writer(rng)
    w.bound = 6.28 if same_legs else 2.5  # same legs: the nominal posture inside on every leg
    w.parts.append('<robot name="drawn">')
    w.link("base", np.eye(4))
    drawn = []
    for k in range(6):
        left = k < 3
        yaw = (1 if left else -1) * (np.pi / 4 + (k % 3) * np.pi / 4) + rng.uniform(-0.2, 0.2)
        root = [0.15 * np.cos(yaw), 0.1 * np.sin(yaw), rng.uniform(-0.03, 0.03)]
        mount = _frame(_rz(yaw), root)
        a1, h = rng.uniform(0.0, 0.06), rng.uniform(-0.05, 0.05)
        l2, l3 = rng.uniform(0.04, 0.15), rng.uniform(0.06, 0.2)
        femur_line, tibia_line = rng.uniform(-0.5, 0.5), rng.uniform(-2.0, -0.6)
        hip = np.array([a1, rng.uniform(-0.04, 0.04), h])
        knee = hip + np.array(
            [l2 * np.cos(femur_line), rng.uniform(-0.03, 0.03), l2 * np.sin(femur_line)]
        )
        lateral = rng.uniform(-0.03, 0.03)
        if same_legs:
            first = first or (a1, h, l2, l3, femur_line, tibia_line, hip, knee, lateral)
            a1, h, l2, l3, femur_line, tibia_line, hip, knee, lateral = first
            mount = _frame(_rz(yaw), [root[0], root[1], 0.0])
        foot = [knee[0] + l3 * np.cos(tibia_line), lateral, knee[2] + l3 * np.sin(tibia_line)]
        flip = _rx(np.pi) if left else np.eye(3)  # mirrored: the yaw axis points down
        yaw_axis = ("0 0 -1" if left else "0 0 1") if rng.random() < 0.5 else "0 0 1"
        leg = f"leg{k}"
        w.joint(
            f"{leg}_j1",
            "revolute",
            "base",
            f"{leg}_coxa",
            mount @ _frame(flip @ _rz(rng.uniform(-3, 3)), [0, 0, 0]),
            yaw_axis,
        )
        parent = f"{leg}_coxa"
        if rng.random() < 0.5:  # a fixed link inside the coxa
            w.joint(
                f"{leg}_fix1",
                "fixed",
                parent,
                f"{leg}_bracket",
                mount @ _frame(_rx(0.3), [0.01, 0, 0]),
            )
            parent = f"{leg}_bracket"
        frame, axis = _pitch_frame(rng, hip)
        kind = "revolute" if same_legs else "continuous"  # Pinocchio: a continuous q is (cos, sin)
        w.joint(f"{leg}_j2", kind, parent, f"{leg}_femur", mount @ frame, axis)
        frame, axis = _pitch_frame(rng, knee)
        w.joint(f"{leg}_j3", "revolute", f"{leg}_femur", f"{leg}_tibia", mount @ frame, axis)
        parent = f"{leg}_tibia"
        if rng.random() < 0.5:  # a fixed link inside the tibia
            w.joint(
                f"{leg}_fix3",
                "fixed",
                parent,
                f"{leg}_shin",
                w.frames[parent] @ _frame(_rz(0.7), [0.0, 0.02, 0.0]),
            )
            parent = f"{leg}_shin"
        if foot_link:
            w.joint(
                f"{leg}_tip", "fixed", parent, f"{leg}_foot_link", mount @ _frame(_rz(0.2), foot)
            )
        drawn.append(DrawnLeg(a1, h, l2, l3, lateral + 0.0, mount))
    w.parts.append("</robot>")
    return "\n".join(w.parts), drawn
