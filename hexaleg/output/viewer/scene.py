"""The meshcat scene of what the body can and cannot do.

The scene holds the ground, the footholds, the robot at its nominal stance
(``/hexaleg/nominal``), and the twelve axis-locked extreme poses, each under
``/hexaleg/extremes/<axis><sign>`` (hidden until ticked in the scene tree) with
the link whose joint stops it drawn in red. One animation plays the nominal
robot out to each extreme and back, in turn. Optionally a leg's swing-phase
workspace is drawn as a point cloud.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg._io import atomic_write_text
from hexaleg.cause import Cause
from hexaleg.exceptions import ParameterError
from hexaleg.output.viewer.legend import HIGHLIGHT, torque_colour, with_legend
from hexaleg.output.viewer.server import LoopbackServer, client
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.configurations import stance_configurations
from hexaleg.stance.extremes import Extreme, FlexibilityResult
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.statics.forces import StaticState
from hexaleg.statics.loads import LoadsAnalysis
from hexaleg.swing.workspace import monte_carlo_workspace

ROOT = "hexaleg"
ANIMATION_FPS = 30
FRAMES_PER_LEG_OF_TRIP = 20  # nominal → extreme; the way back takes as many


def extreme_name(extreme: Extreme) -> str:
    """Scene-tree name of an extreme, e.g. ``x+`` or ``yaw-``."""
    return extreme.name


def build_scene(
    viewer: Any,
    model: HexapodModel,
    result: FlexibilityResult,
    workspace_leg: str | None = None,
    workspace_samples: int = 4000,
    loads: LoadsAnalysis | None = None,
) -> None:
    """Load the hexapod, footholds, ground, extremes and animation into ``viewer``.

    Args:
        viewer: A ``meshcat.Visualizer``.
        model: The hexapod's Pinocchio model (its URDF gives the geometry).
        result: Axis-locked extremes to show.
        workspace_leg: If given, draw this leg's Monte Carlo workspace as a point cloud.
        workspace_samples: Points in that cloud.
        loads: If given, each stance leg's coxa, femur and tibia is coloured by its
            joint's |τ| / rated at each pose shown (legend: :func:`.legend.with_legend`,
            beside the scene in the page).

    """
    geometry = StanceGeometry.from_model(model, result.legs)
    visual = pin.buildGeomFromUrdfString(model.model, model.urdf, pin.GeometryType.VISUAL)
    viewer.delete()
    viewer["/Grid"].set_property("visible", False)
    _add_ground(viewer, geometry)
    _add_footholds(viewer, geometry)
    nominal = _robot(viewer, model, visual, f"{ROOT}/nominal")
    if loads is not None:
        _colour_by_torque(nominal, visual, loads.nominal, model.design.rated_torques)
    nominal.display(model.nominal_configuration())
    _add_extremes(viewer, model, geometry, visual, nominal, result, loads)
    if workspace_leg is not None:
        _add_workspace(viewer, model, workspace_leg, workspace_samples)
    _place_camera(viewer, geometry)


def _robot(viewer: Any, model: HexapodModel, visual: Any, root: str) -> Any:
    """A copy of the robot's visuals under ``root`` in the scene tree."""
    from pinocchio.visualize import MeshcatVisualizer

    robot = MeshcatVisualizer(model.model, None, visual)
    robot.initViewer(viewer=viewer)
    robot.loadViewerModel(rootNodeName=root)
    return robot


def _add_extremes(
    viewer: Any,
    model: HexapodModel,
    geometry: StanceGeometry,
    visual: Any,
    nominal: Any,
    result: FlexibilityResult,
    loads: LoadsAnalysis | None,
) -> None:
    """Each extreme as a hidden robot (its limiting links red), and the animation to each."""
    from meshcat.animation import Animation

    animation = Animation(default_framerate=ANIMATION_FPS)
    frame = 0
    for k, extreme in enumerate(result.extremes):
        path = f"{ROOT}/extremes/{extreme_name(extreme)}"
        copy = _robot(viewer, model, visual, path)
        if loads is not None:
            state = loads.extremes[k].state
            _colour_by_torque(copy, visual, state, model.design.rated_torques)
        for obj in _limiting_objects(visual, extreme):
            copy.loadViewerGeometryObject(obj, pin.GeometryType.VISUAL, list(HIGHLIGHT))
        copy.display(_extreme_configuration(model, geometry, extreme))
        viewer[path].set_property("visible", False)
        frame = _animate_trip(animation, viewer, nominal, model, geometry, extreme, frame)
    viewer.set_animation(animation, play=False, repetitions=1)


def _add_footholds(viewer: Any, geometry: StanceGeometry) -> None:
    import meshcat.geometry as mg

    for leg, foothold in zip(geometry.legs, geometry.footholds, strict=True):
        node = viewer[f"{ROOT}/footholds/{leg}"]
        node.set_object(mg.Sphere(0.03), mg.MeshLambertMaterial(color=0xD62728))
        node.set_transform(_translation(foothold))


def _place_camera(
    viewer: Any, geometry: StanceGeometry, centre: Sequence[float] = (0.0, 0.0), spread: float = 0.0
) -> None:
    """The default camera at the front right, above, far enough to see every foothold.

    For a robot that travels, ``centre`` (x, y) [m] is the middle of its path and
    ``spread`` [m] how far from there the body goes: the camera looks at that middle from
    far enough to see every foothold along the way.
    """
    viewer["/Cameras/default"].set_transform(_translation([*centre, 0.0]))
    reach = float(np.abs(geometry.footholds[:, :2]).max()) + spread
    viewer["/Cameras/default/rotated/<object>"].set_property(
        "position",
        [1.6 * reach, 1.1 * reach, 1.6 * reach],  # three.js axes: y up
    )


def _colour_by_torque(robot: Any, visual: Any, state: StaticState, rated: Sequence[float]) -> None:
    """Reload each stance leg's links in the colour of its joint's |τ| / rated."""
    ratios = np.abs(state.joint_torques) / np.asarray(rated)
    for leg, leg_ratios in zip(state.legs, ratios, strict=True):
        for joint, ratio in zip(("root", "hip", "knee"), leg_ratios, strict=True):
            link = f"{leg}_{JOINT_LINKS[joint]}"
            for obj in visual.geometryObjects:
                if obj.name.rsplit("_", 1)[0] == link:
                    robot.loadViewerGeometryObject(
                        obj, pin.GeometryType.VISUAL, list(torque_colour(ratio))
                    )


def _add_ground(viewer: Any, geometry: StanceGeometry) -> float:
    """A square of ground around the footholds, 1 cm thick; return its side [m]."""
    import meshcat.geometry as mg

    span = 2.5 * (np.abs(geometry.footholds[:, :2]).max() + 0.2)
    node = viewer[f"{ROOT}/ground"]
    node.set_object(mg.Box([span, span, 0.01]), mg.MeshLambertMaterial(color=0xC8C8C8, opacity=0.9))
    node.set_transform(_translation([0.0, 0.0, -0.005]))
    return float(span)


def _add_workspace(viewer: Any, model: HexapodModel, leg: str, samples: int) -> None:
    import meshcat.geometry as mg

    if leg not in model.leg_names:
        raise ParameterError("--workspace", leg, f"legs are {', '.join(model.leg_names)}")
    cloud = monte_carlo_workspace(model.design, samples=samples, seed=0)
    root = model.nominal_base_pose() * model.root_placements()[leg]
    points = cloud.points @ root.rotation.T + root.translation
    heights = (cloud.points[:, 2] - cloud.points[:, 2].min()) / max(
        np.ptp(cloud.points[:, 2]), 1e-9
    )
    colors = np.stack([0.2 + 0.6 * heights, 0.4 * np.ones_like(heights), 1.0 - 0.6 * heights])
    viewer[f"{ROOT}/workspace/{leg}"].set_object(
        mg.PointCloud(
            position=points.T.astype(np.float32), color=colors.astype(np.float32), size=0.01
        )
    )


def _extreme_configuration(
    model: HexapodModel, geometry: StanceGeometry, extreme: Extreme, share: float = 1.0
) -> np.ndarray:
    """The robot at ``share`` of the way from nominal to the extreme's pose (free or not)."""
    return stance_configurations(model, geometry, share * np.asarray(extreme.pose))[0]


def _limiting_objects(visual: Any, extreme: Extreme) -> list[Any]:
    """Visual objects to highlight for every binding constraint.

    The link a limiting joint moves, a whole leg out of reach, or the body on the ground.
    """
    links = {link for cause in extreme.binding for link in _limiting_links(cause)}
    return [obj for obj in visual.geometryObjects if obj.name.rsplit("_", 1)[0] in links]


def _limiting_links(cause: Cause) -> tuple[str, ...]:
    if cause.kind == "joint":
        return (f"{cause.leg}_{JOINT_LINKS[cause.joint or '']}",)
    if cause.kind == "reach":
        return tuple(f"{cause.leg}_{part}" for part in ("coxa", "femur", "tibia", "foot"))
    if cause.kind == "ground":
        return ("base_link",)
    return ()


JOINT_LINKS = {"root": "coxa", "hip": "femur", "knee": "tibia"}
"""The link each leg joint moves."""


def _animate_trip(
    animation: Any,
    viewer: Any,
    nominal: Any,
    model: HexapodModel,
    geometry: StanceGeometry,
    extreme: Extreme,
    frame: int,
) -> int:
    """Keyframes of the nominal robot going out to ``extreme`` and back; return the next frame."""
    steps = np.concatenate(
        [
            np.linspace(0, 1, FRAMES_PER_LEG_OF_TRIP + 1),
            np.linspace(1, 0, FRAMES_PER_LEG_OF_TRIP + 1)[1:],
        ]
    )
    visual_model, visual_data = nominal.visual_model, nominal.visual_data
    for s in steps:
        q = _extreme_configuration(model, geometry, extreme, s)
        pin.forwardKinematics(model.model, nominal.data, q)
        pin.updateGeometryPlacements(model.model, nominal.data, visual_model, visual_data)
        with animation.at_frame(viewer, frame) as keyframe:
            for k, obj in enumerate(visual_model.geometryObjects):
                name = nominal.getViewerNodeName(obj, pin.GeometryType.VISUAL)
                keyframe[name].set_transform(visual_data.oMg[k].homogeneous)
        frame += 1
    return frame


def _translation(position: Sequence[float]) -> np.ndarray:
    transform = np.eye(4)
    transform[:3, 3] = position
    return transform


def static_html(
    model: HexapodModel,
    result: FlexibilityResult,
    workspace_leg: str | None = None,
    loads: LoadsAnalysis | None = None,
) -> str:
    """A self-contained HTML page of the scene (no server needed to view it)."""
    with LoopbackServer() as server:
        viewer = client(server)
        build_scene(viewer, model, result, workspace_leg, loads=loads)
        html = viewer.static_html()
        if loads is not None:
            html = with_legend(html)
        viewer.window.zmq_socket.close(linger=0)
    return html


def write_static_html(
    model: HexapodModel,
    result: FlexibilityResult,
    path: str | os.PathLike[str],
    workspace_leg: str | None = None,
    loads: LoadsAnalysis | None = None,
) -> Path:
    """Write :func:`static_html` to ``path`` atomically."""
    return atomic_write_text(path, static_html(model, result, workspace_leg, loads))
