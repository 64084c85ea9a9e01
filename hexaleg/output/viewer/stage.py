"""What every hexaleg scene stands on: the ground, copies of the robot, the camera.

Both scenes, the body's extremes (:mod:`.scene`) and a walking period (:mod:`.gait`),
start from a :class:`Stage`: the meshcat tree cleared and the ground laid under the
stance, then add robots under their own nodes (:meth:`Stage.robot`), move them in
keyframes (:meth:`Stage.pose`), colour their links (:meth:`Stage.link_objects`), and
end with the camera placed (:meth:`Stage.place_camera`).

Links are found by the joint that carries them (:meth:`Stage.joint_objects`), not by
name, so the same scene draws hexaleg's robot and an imported one whose links are named
as its file names them.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.limits import LEG_JOINTS
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.geometry import StanceGeometry

ROOT = "hexaleg"
"""The scene tree's node under which hexaleg draws everything."""

BODY_JOINT = 1
"""Pinocchio joint id of the free flyer: what carries the body's visuals."""


@dataclass(frozen=True)
class Stage:
    """A meshcat scene cleared for one robot, with the ground under its stance.

    Attributes:
        viewer: The ``meshcat.Visualizer`` drawn into.
        model: The hexapod's Pinocchio model (its URDF gives the geometry).
        geometry: The stance the ground and the camera are sized for.
        visual: The robot's visual geometry (:meth:`.HexapodModel.visual_model`).

    """

    viewer: Any
    model: HexapodModel
    geometry: StanceGeometry
    visual: pin.GeometryModel

    @classmethod
    def set_up(cls, viewer: Any, model: HexapodModel, legs: str | Sequence[str]) -> Stage:
        """Clear ``viewer``, hide meshcat's grid and lay the ground under ``legs``' stance."""
        import meshcat.geometry as mg

        geometry = StanceGeometry.from_model(model, legs)
        visual = model.visual_model()
        viewer.delete()
        viewer["/Grid"].set_property("visible", False)
        span = _ground_side(geometry)
        node = viewer[f"{ROOT}/ground"]
        node.set_object(
            mg.Box([span, span, 0.01]), mg.MeshLambertMaterial(color=0xC8C8C8, opacity=0.9)
        )
        node.set_transform(translation([0.0, 0.0, -0.005]))
        return cls(viewer, model, geometry, visual)

    def robot(self, root: str) -> Any:
        """A copy of the robot's visuals under ``root`` in the scene tree."""
        from pinocchio.visualize import MeshcatVisualizer

        robot = MeshcatVisualizer(self.model.model, None, self.visual)
        robot.initViewer(viewer=self.viewer)
        robot.loadViewerModel(rootNodeName=root)
        return robot

    def link_objects(self, links: Collection[str]) -> list[Any]:
        """The visual objects of ``links`` (URDF link names, e.g. ``lf_femur``)."""
        frames = self.model.model.frames
        return [obj for obj in self.visual.geometryObjects if frames[obj.parentFrame].name in links]

    def carried_by(self, joints: Collection[int]) -> list[Any]:
        """The visual objects that ``joints`` (Pinocchio joint ids) move directly."""
        return [obj for obj in self.visual.geometryObjects if obj.parentJoint in joints]

    def joint_objects(self, leg: str, joints: Collection[str] = LEG_JOINTS) -> list[Any]:
        """The visual objects ``leg``'s ``joints`` (``"root"``, ...) move: its segments' links."""
        ids = self.model.leg_joint_ids(leg)
        return self.carried_by({ids[LEG_JOINTS.index(joint)] for joint in joints})

    def pose(self, keyframe: Any, robot: Any, q: np.ndarray) -> None:
        """Set, in one animation keyframe, every visual of ``robot`` at configuration ``q``."""
        pin.forwardKinematics(self.model.model, robot.data, q)
        pin.updateGeometryPlacements(self.model.model, robot.data, self.visual, robot.visual_data)
        for k, obj in enumerate(self.visual.geometryObjects):
            name = robot.getViewerNodeName(obj, pin.GeometryType.VISUAL)
            keyframe[name].set_transform(robot.visual_data.oMg[k].homogeneous)

    def place_camera(self, centre: Sequence[float] = (0.0, 0.0), spread: float = 0.0) -> None:
        """The default camera at the front right, above, far enough to see every foothold.

        For a robot that travels, ``centre`` (x, y) [m] is the middle of its path and
        ``spread`` [m] how far from there the body goes: the camera looks at that middle
        from far enough to see every foothold along the way.
        """
        self.viewer["/Cameras/default"].set_transform(translation([*centre, 0.0]))
        reach = float(np.abs(self.geometry.footholds[:, :2]).max()) + spread
        self.viewer["/Cameras/default/rotated/<object>"].set_property(
            "position",
            [1.6 * reach, 1.1 * reach, 1.6 * reach],  # three.js axes: y up
        )

    def stretch_ground(self, low: Sequence[float], high: Sequence[float]) -> None:
        """Stretch the ground under a whole path of the body, from ``low`` to ``high`` (x, y) [m].

        The ground is a square around the stance's footholds at the origin; it grows by
        the path's extent, so every foothold of every frame stays on it.
        """
        low_xy, high_xy = np.asarray(low, dtype=float), np.asarray(high, dtype=float)
        stretch = np.eye(4)
        stretch[:2, :2] = np.diag(1.0 + (high_xy - low_xy) / _ground_side(self.geometry))
        stretch[:2, 3] = (low_xy + high_xy) / 2
        stretch[2, 3] = -0.005
        self.viewer[f"{ROOT}/ground"].set_transform(stretch)


def _ground_side(geometry: StanceGeometry) -> float:
    """Side [m] of the square of ground laid under ``geometry``'s footholds."""
    return float(2.5 * (np.abs(geometry.footholds[:, :2]).max() + 0.2))


def translation(position: Sequence[float]) -> np.ndarray:
    """The homogeneous transform [-, m] of a pure translation to ``position`` [m]."""
    transform = np.eye(4)
    transform[:3, 3] = position
    return transform
