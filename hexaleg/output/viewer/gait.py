"""The meshcat animation of one gait period, legs coloured by |τ|/rated at each instant.

The scene holds the ground and the robot (``/hexaleg/gait``); one animation plays the
period in real time (one keyframe per sample): the body walking at its constant velocity,
each leg's coxa, femur and tibia in the colour of its root, hip and knee's |τ|/rated
torque at that instant (viridis, as the statics view; the legend beside the scene in the
static page). Served by ``hexaleg view --gait`` or written as a static page by
``hexaleg gait --html``.
"""

from __future__ import annotations

import os
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg._io import write_text
from hexaleg._typing import ArrayF
from hexaleg.gait.analysis import GaitAnalysis
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.viewer.legend import torque_colour, with_legend
from hexaleg.output.viewer.scene import JOINT_LINKS, ROOT, _add_ground, _place_camera, _robot
from hexaleg.output.viewer.server import LoopbackServer, client
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.geometry import StanceGeometry

NODE = f"{ROOT}/gait"
"""The walking robot's node in the scene tree."""
ANIMATION_PATH = "/zz_hexaleg_gait_animation"
"""Where the server keeps the animation: after every object of the scene (see _send_last)."""


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
        np.abs(analysis.joint_torques) / np.array(analysis.design.rated_torques),
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

    """
    from meshcat.animation import Animation

    geometry = StanceGeometry.from_model(model, "all")
    visual = pin.buildGeomFromUrdfString(model.model, model.urdf, pin.GeometryType.VISUAL)
    viewer.delete()
    viewer["/Grid"].set_property("visible", False)
    span = _add_ground(viewer, geometry)
    robot = _robot(viewer, model, visual, NODE)
    robot.display(configurations[0])
    animation = Animation(default_framerate=max(1, round(frame_rate)))
    links = _leg_links(robot, visual, model.leg_names)
    for frame, q in enumerate(configurations):
        pin.forwardKinematics(model.model, robot.data, q)
        pin.updateGeometryPlacements(model.model, robot.data, visual, robot.visual_data)
        with animation.at_frame(viewer, frame) as keyframe:
            for k, obj in enumerate(visual.geometryObjects):
                name = robot.getViewerNodeName(obj, pin.GeometryType.VISUAL)
                keyframe[name].set_transform(robot.visual_data.oMg[k].homogeneous)
            for (leg, joint), names in links.items():
                red, green, blue, _ = torque_colour(float(ratios[frame, leg, joint]))
                for name in names:
                    keyframe[name]["<object>"].set_property(
                        "material.color", "color", [red, green, blue]
                    )
    _send_last(viewer, animation)
    path = np.asarray(configurations)[:, :2]
    low, high = path.min(axis=0), path.max(axis=0)
    _stretch_ground(viewer, span, low, high)
    _place_camera(viewer, geometry, (low + high) / 2, float(np.linalg.norm(high - low)) / 2)


def _stretch_ground(viewer: Any, span: float, low: ArrayF, high: ArrayF) -> None:
    """Stretch the ground under the body's whole path, from ``low`` to ``high`` (x, y) [m].

    The ground is a square of side ``span`` [m] around the footholds at the origin; it
    grows by the path's extent, so every foothold of every frame stays on it.
    """
    stretch = np.eye(4)
    stretch[:2, :2] = np.diag(1.0 + (high - low) / span)
    stretch[:2, 3] = (low + high) / 2
    stretch[2, 3] = -0.005
    viewer[f"{ROOT}/ground"].set_transform(stretch)


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


def _leg_links(
    robot: Any, visual: pin.GeometryModel, legs: tuple[str, ...]
) -> dict[tuple[int, int], list[str]]:
    """Scene names of each (leg, joint)'s link geometry: the link each joint moves."""
    links: dict[tuple[int, int], list[str]] = {}
    for i, leg in enumerate(legs):
        for j, joint in enumerate(LEG_JOINTS):
            link = f"{leg}_{JOINT_LINKS[joint]}"
            links[(i, j)] = [
                robot.getViewerNodeName(obj, pin.GeometryType.VISUAL)
                for obj in visual.geometryObjects
                if obj.name.rsplit("_", 1)[0] == link
            ]
    return links


def gait_html(model: HexapodModel, analysis: GaitAnalysis) -> str:
    """A self-contained HTML page of the animation (no server needed to view it)."""
    return _static_page(lambda viewer: build_gait_scene(viewer, model, analysis))


def motion_html(
    model: HexapodModel, configurations: ArrayF, frame_rate: float, ratios: ArrayF
) -> str:
    """A self-contained HTML page of :func:`build_motion_scene` (no server needed)."""
    return _static_page(
        lambda viewer: build_motion_scene(viewer, model, configurations, frame_rate, ratios)
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


def _static_page(build: Callable[[Any], None]) -> str:
    """The static page of a scene ``build`` loads into a viewer, with the torque legend."""
    with LoopbackServer() as server:
        viewer = client(server)
        build(viewer)
        html: str = with_legend(viewer.static_html())
        viewer.window.zmq_socket.close(linger=0)
    return html


def write_gait_html(
    model: HexapodModel, analysis: GaitAnalysis, path: str | os.PathLike[str]
) -> Path:
    """Write :func:`gait_html` to ``path`` atomically."""
    return write_text(path, gait_html(model, analysis))
