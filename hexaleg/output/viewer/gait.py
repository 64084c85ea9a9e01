"""The meshcat animation of one gait period, legs coloured by |τ|/rated at each instant.

The scene holds the ground and the robot (``/hexaleg/gait``); one animation plays the
period in real time (one keyframe per sample, at most :data:`MAX_ANIMATION_FRAMES`): the
body walking at its constant velocity,
each leg's coxa, femur and tibia in the colour of its root, hip and knee's |τ|/rated
torque at that instant (viridis, as the statics view; no link is red: nothing stops a
gait as a limit stops an extreme). The legend beside the scene, served by
``hexaleg view --gait`` or in the static page ``hexaleg gait --html`` writes, says so
(:data:`.legend.GAIT_LEGEND`).
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg._io import write_text
from hexaleg._typing import ArrayF
from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.viewer.legend import GAIT_LEGEND, torque_colour
from hexaleg.output.viewer.server import static_page
from hexaleg.output.viewer.stage import ROOT, Stage
from hexaleg.robot.model import HexapodModel
from hexaleg.statics.ratings import rating_use

NODE = f"{ROOT}/gait"
"""The walking robot's node in the scene tree."""
ANIMATION_PATH = "/zz_hexaleg_gait_animation"
"""Where the server keeps the animation: after every object of the scene (see _send_last)."""
MAX_ANIMATION_FRAMES = 2000
"""Most keyframes an animation holds, whatever the samples or the run's length: past it,
every k-th frame is a keyframe, at its own time (the browser moves between keyframes
smoothly, still in real time), so a page's size and the time to write it stay bounded."""


def build_gait_scene(viewer: Any, model: HexapodModel, analysis: GaitAnalysis) -> None:
    """Load the ground, the robot and the period's animation into ``viewer``.

    Args:
        viewer: A ``meshcat.Visualizer``.
        model: The hexapod's Pinocchio model (its URDF gives the geometry).
        analysis: The gait period to play.

    """
    build_motion_scene(
        viewer,
        model,
        analysis.configurations,
        analysis.gait.samples / analysis.gait.period,  # real time
        rating_use(analysis.joint_torques, analysis.design.rated_torques),
    )


def build_motion_scene(
    viewer: Any, model: HexapodModel, configurations: ArrayF, frame_rate: float, ratios: ArrayF
) -> None:
    """Load the ground under the whole path, the robot and its animation into ``viewer``.

    Args:
        viewer: A ``meshcat.Visualizer``.
        model: The hexapod's Pinocchio model (its URDF gives the geometry).
        configurations: The robot's configuration in each frame (F, nq).
        frame_rate: Frames per second [1/s].
        ratios: Each leg joint's |τ|/rated in each frame (F, legs, 3), its link's colour.

    At most :data:`MAX_ANIMATION_FRAMES` of the frames become keyframes.

    """
    from meshcat.animation import Animation

    stage = Stage.set_up(viewer, model, "all")
    robot = stage.robot(NODE)
    robot.display(configurations[0])
    animation = Animation(default_framerate=max(1, round(frame_rate)))
    links = _leg_links(stage, robot, model.leg_names)
    every = math.ceil(len(configurations) / MAX_ANIMATION_FRAMES)
    for frame in range(0, len(configurations), every):  # each keyframe at its own time
        with animation.at_frame(viewer, frame) as keyframe:
            stage.pose(keyframe, robot, configurations[frame])
            for (leg, joint), names in links.items():
                red, green, blue, _ = torque_colour(float(ratios[frame, leg, joint]))
                for name in names:
                    keyframe[name]["<object>"].set_property(
                        "material.color", "color", [red, green, blue]
                    )
    _send_last(viewer, animation)
    path = np.asarray(configurations)[:, :2]
    low, high = path.min(axis=0), path.max(axis=0)
    stage.stretch_ground(low, high)
    stage.place_camera((low + high) / 2, float(np.linalg.norm(high - low)) / 2)


def _send_last(viewer: Any, animation: Any) -> None:
    """Send the animation so that a page replaying the scene loads it after every object.

    meshcat's server replays its scene tree depth-first and keeps an animation at the
    command's path, the root by default: a page then loads the animation before the
    links' meshes exist and their colour tracks bind to nothing. Kept at a path added
    after the robot's, it comes last. (The transforms bind to group nodes that persist.)
    """
    from meshcat.commands import SetAnimation

    command = SetAnimation(animation, play=True, repetitions=1000).lower()
    command["path"] = ANIMATION_PATH
    viewer.window.send(_Lowered(command))


class _Lowered:
    """A meshcat command already lowered to its message."""

    def __init__(self, command: dict[str, Any]) -> None:
        self.command = command

    def lower(self) -> dict[str, Any]:
        return self.command


def _leg_links(stage: Stage, robot: Any, legs: tuple[str, ...]) -> dict[tuple[int, int], list[str]]:
    """Scene names of each (leg, joint)'s link geometry: the link each joint moves."""
    return {
        (i, j): [
            robot.getViewerNodeName(obj, pin.GeometryType.VISUAL)
            for obj in stage.joint_objects(leg, (joint,))
        ]
        for i, leg in enumerate(legs)
        for j, joint in enumerate(LEG_JOINTS)
    }


def gait_html(model: HexapodModel, analysis: GaitAnalysis) -> str:
    """A self-contained HTML page of the animation (no server needed to view it)."""
    return static_page(lambda viewer: build_gait_scene(viewer, model, analysis), GAIT_LEGEND)


def motion_html(
    model: HexapodModel, configurations: ArrayF, frame_rate: float, ratios: ArrayF
) -> str:
    """A self-contained HTML page of :func:`build_motion_scene` (no server needed)."""
    return static_page(
        lambda viewer: build_motion_scene(viewer, model, configurations, frame_rate, ratios),
        GAIT_LEGEND,
    )


def write_motion_html(
    model: HexapodModel,
    configurations: ArrayF,
    frame_rate: float,
    ratios: ArrayF,
    path: str | os.PathLike[str],
) -> Path:
    """Write :func:`motion_html` to ``path`` atomically (a simulated walk, say)."""
    return write_text(path, motion_html(model, configurations, frame_rate, ratios))


def write_gait_html(
    model: HexapodModel, analysis: GaitAnalysis, path: str | os.PathLike[str]
) -> Path:
    """Write :func:`gait_html` to ``path`` atomically."""
    return write_text(path, gait_html(model, analysis))
