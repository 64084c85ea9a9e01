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
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg._io import write_text
from hexaleg.cause import Cause
from hexaleg.exceptions import ParameterError
from hexaleg.limits import LEG_JOINTS
from hexaleg.output.viewer.legend import HIGHLIGHT, STATICS_LEGEND, torque_colour
from hexaleg.output.viewer.server import static_page
from hexaleg.output.viewer.stage import BODY_JOINT, ROOT, Stage, translation
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.configurations import stance_configurations
from hexaleg.stance.extremes import Extreme, FlexibilityResult
from hexaleg.statics.forces import StaticState
from hexaleg.statics.loads import LoadsAnalysis
from hexaleg.statics.ratings import rating_use
from hexaleg.swing.workspace import monte_carlo_workspace

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
            joint's |τ| / rated at each pose shown (legend beside the scene in the
            page: :data:`.legend.STATICS_LEGEND`).

    """
    stage = Stage.set_up(viewer, model, result.legs)
    _add_footholds(stage)
    nominal = stage.robot(f"{ROOT}/nominal")
    if loads is not None:
        _colour_by_torque(stage, nominal, loads.nominal)
    nominal.display(model.nominal_configuration())
    _add_extremes(stage, nominal, result, loads)
    if workspace_leg is not None:
        _add_workspace(viewer, model, workspace_leg, workspace_samples)
    stage.place_camera()


def _add_extremes(
    stage: Stage, nominal: Any, result: FlexibilityResult, loads: LoadsAnalysis | None
) -> None:
    """Each extreme as a hidden robot (its limiting links red), and the animation to each."""
    from meshcat.animation import Animation

    animation = Animation(default_framerate=ANIMATION_FPS)
    frame = 0
    for k, extreme in enumerate(result.extremes):
        path = f"{ROOT}/extremes/{extreme_name(extreme)}"
        copy = stage.robot(path)
        if loads is not None:
            _colour_by_torque(stage, copy, loads.extremes[k].state)
        for obj in _limiting_objects(stage, extreme):
            copy.loadViewerGeometryObject(obj, pin.GeometryType.VISUAL, list(HIGHLIGHT))
        copy.display(_extreme_configuration(stage, extreme))
        stage.viewer[path].set_property("visible", False)
        frame = _animate_trip(animation, stage, nominal, extreme, frame)
    stage.viewer.set_animation(animation, play=False, repetitions=1)


def _add_footholds(stage: Stage) -> None:
    import meshcat.geometry as mg

    for leg, foothold in zip(stage.geometry.legs, stage.geometry.footholds, strict=True):
        node = stage.viewer[f"{ROOT}/footholds/{leg}"]
        node.set_object(mg.Sphere(0.03), mg.MeshLambertMaterial(color=0x222222))  # red: limits
        node.set_transform(translation(foothold))


def _colour_by_torque(stage: Stage, robot: Any, state: StaticState) -> None:
    """Reload each stance leg's links in the colour of its joint's |τ| / rated.

    Without ratings, |τ| over each joint type's largest (:func:`rating_use`).
    """
    ratios = rating_use(state.joint_torques, stage.model.design.rated_torques)
    for leg, leg_ratios in zip(state.legs, ratios, strict=True):
        for joint, ratio in zip(LEG_JOINTS, leg_ratios, strict=True):
            colour = list(torque_colour(ratio))
            for obj in stage.joint_objects(leg, (joint,)):
                robot.loadViewerGeometryObject(obj, pin.GeometryType.VISUAL, colour)


def _add_workspace(viewer: Any, model: HexapodModel, leg: str, samples: int) -> None:
    import meshcat.geometry as mg

    if leg not in model.leg_names:
        raise ParameterError("--workspace", leg, f"legs are {', '.join(model.leg_names)}")
    cloud = monte_carlo_workspace(model.design, samples, 0, leg=model.leg_geometry(leg))
    root = model.nominal_base_pose() * model.root_placements()[leg]
    points = cloud.points @ root.rotation.T + root.translation
    heights = (cloud.points[:, 2] - cloud.points[:, 2].min()) / max(
        np.ptp(cloud.points[:, 2]), 1e-9
    )
    colors = np.tile(0.25 + 0.6 * heights, (3, 1))  # grey, lighter higher: red means a limit
    viewer[f"{ROOT}/workspace/{leg}"].set_object(
        mg.PointCloud(
            position=points.T.astype(np.float32), color=colors.astype(np.float32), size=0.01
        )
    )


def _extreme_configuration(stage: Stage, extreme: Extreme, share: float = 1.0) -> np.ndarray:
    """The robot at ``share`` of the way from nominal to the extreme's pose (free or not)."""
    pose = share * np.asarray(extreme.pose)
    configuration: np.ndarray = stance_configurations(stage.model, stage.geometry, pose)[0]
    return configuration


def _limiting_objects(stage: Stage, extreme: Extreme) -> list[Any]:
    """The visuals to highlight for every binding constraint, each once.

    The link a limiting joint moves, a whole leg out of reach, the body on the ground, or
    the two links that touch.
    """
    found = {id(obj): obj for cause in extreme.binding for obj in _cause_objects(stage, cause)}
    return list(found.values())


def _cause_objects(stage: Stage, cause: Cause) -> list[Any]:
    if cause.kind == "joint" and cause.leg and cause.joint:
        return stage.joint_objects(cause.leg, (cause.joint,))
    if cause.kind == "reach" and cause.leg:
        return stage.joint_objects(cause.leg)
    if cause.kind == "ground":
        return stage.carried_by({BODY_JOINT})
    if cause.kind == "collision" and cause.links:
        return stage.link_objects(cause.links)
    return []


def _animate_trip(animation: Any, stage: Stage, nominal: Any, extreme: Extreme, frame: int) -> int:
    """Keyframes of the nominal robot going out to ``extreme`` and back; return the next frame."""
    steps = np.concatenate(
        [
            np.linspace(0, 1, FRAMES_PER_LEG_OF_TRIP + 1),
            np.linspace(1, 0, FRAMES_PER_LEG_OF_TRIP + 1)[1:],
        ]
    )
    for s in steps:
        with animation.at_frame(stage.viewer, frame) as keyframe:
            stage.pose(keyframe, nominal, _extreme_configuration(stage, extreme, s))
        frame += 1
    return frame


def static_html(
    model: HexapodModel,
    result: FlexibilityResult,
    workspace_leg: str | None = None,
    loads: LoadsAnalysis | None = None,
) -> str:
    """A self-contained HTML page of the scene (no server needed to view it).

    With ``loads``, the links are coloured by torque and the legend stands beside them.
    """
    return static_page(
        lambda viewer: build_scene(viewer, model, result, workspace_leg, loads=loads),
        None if loads is None else STATICS_LEGEND,
    )


def write_static_html(
    model: HexapodModel,
    result: FlexibilityResult,
    path: str | os.PathLike[str],
    workspace_leg: str | None = None,
    loads: LoadsAnalysis | None = None,
) -> Path:
    """Write :func:`static_html` to ``path`` atomically."""
    return write_text(path, static_html(model, result, workspace_leg, loads))
