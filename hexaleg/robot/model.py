"""The hexapod's Pinocchio model, built from the rendered URDF.

:class:`HexapodModel` is the free-flyer hexapod (root joint :data:`ROOT_JOINT`,
configuration ``[x, y, z, qx, qy, qz, qw, legs…]``); one leg on a fixed base is
:class:`~hexaleg.robot.leg_model.LegModel`. Frames, joint axes and limits are read from
the model, never re-typed here.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Callable, Iterable, Mapping
from dataclasses import fields
from functools import cached_property
from typing import Any, TypeVar

import numpy as np
import numpy.typing as npt
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.design import HexapodDesign
from hexaleg.exceptions import ModelError
from hexaleg.leg_geometry import LegGeometry
from hexaleg.limits import LEG_JOINTS, JointLimits
from hexaleg.ratings import as_written
from hexaleg.robot.inertia import (
    body_inertial,
    leg_inertials,
    pinocchio_inertia,
    set_armature,
)
from hexaleg.robot.urdf import render_hexapod

ROOT_JOINT = "root_joint"
"""Name of the free-flyer joint that carries the body (the simulators' free joint too)."""


def joint_name(leg: str, joint: str) -> str:
    """URDF name of ``joint`` (root, hip, knee) of leg ``leg``."""
    return f"{leg}_{joint}_joint"


def root_frame_name(leg: str) -> str:
    """Name of the leg-root frame (on the body, z up, x along the coxa at θ1 = 0).

    It is the root joint's own frame: the URDF puts the leg mount on that joint's
    origin, so no massless link is needed (simulators drop or weigh those).
    """
    return joint_name(leg, "root")


def foot_frame_name(leg: str) -> str:
    """Name of the foot frame (at the tibia tip)."""
    return f"{leg}_foot"


class _LegIndex:
    """Where one leg lives in a Pinocchio model: its q/v indices and frame ids."""

    def __init__(
        self, model: pin.Model, leg: str, joints: Iterable[str] | None = None, prefix: str = ""
    ) -> None:
        """``joints``: the leg's three joint names (hexaleg's if omitted); ``prefix``: frames'."""
        self.name = leg
        names = [joint_name(leg, j) for j in LEG_JOINTS] if joints is None else list(joints)
        ids = [_joint_id(model, name) for name in names]
        self.joints = tuple(ids)
        self.q = np.array([model.idx_qs[i] for i in ids])
        self.v = np.array([model.idx_vs[i] for i in ids])
        self.lower = model.lowerPositionLimit[self.q].copy()
        self.upper = model.upperPositionLimit[self.q].copy()
        self.root_frame = _frame_id(model, prefix + root_frame_name(leg))
        self.foot_frame = _frame_id(model, prefix + foot_frame_name(leg))
        self.foot_joint_frame = _frame_id(model, f"{prefix}{leg}_foot_joint")


T = TypeVar("T")

BASE_FRAME = "base_link"
"""The body's frame in hexaleg's URDF (the free flyer's)."""


DERIVED_FIELDS = frozenset(
    "l1 l2 l3 rated_torques rated_speeds nominal_angles actuators battery structure".split()
)
"""The design fields :meth:`HexapodModel.with_design` sets on a copy of a model."""


class HexapodModel:
    """The whole hexapod on a free-flyer root joint, as Pinocchio sees it.

    Attributes:
        design: The design the model was built from.
        urdf: The rendered URDF text.
        model: The Pinocchio model (nq = 7 + 18, nv = 6 + 18).
        data: Pinocchio workspace for ``model``.
        leg_names: Leg names in the design's mounting order.

    """

    def __init__(
        self,
        design: HexapodDesign,
        _model: pin.Model | None = None,
        _legs: dict[str, _LegIndex] | None = None,
        _base: str = BASE_FRAME,
        _structural: dict[str, Any] | None = None,
    ) -> None:
        self.design = design
        self._urdf = None if _model is not None else render_hexapod(design)
        self.model = (
            pin.buildModelFromXML(self._urdf, pin.JointModelFreeFlyer(), ROOT_JOINT)
            if _model is None
            else _model
        )
        self._data: pin.Data | None = None
        self.leg_names: tuple[str, ...] = design.leg_names
        self._legs = _legs or {leg: _LegIndex(self.model, leg) for leg in self.leg_names}
        self._structural: dict[str, Any] = {} if _structural is None else _structural
        if _model is None:
            set_armature(self.model, [leg.v for leg in self._legs.values()], design)
        self.base_frame = _frame_id(self.model, _base)
        self.body_box: ArrayF | None = None  # None: the body's collision shape is the URDF's
        self._collision: pin.GeometryModel | None = None

    def leg_geometry(self, leg: str) -> LegGeometry:
        """``leg``'s general leg: the paper's leg of the design's lengths."""
        self._leg(leg)
        return self._paper_leg

    @cached_property
    def _paper_leg(self) -> LegGeometry:
        """The paper's leg of the design's lengths, every leg's (made once)."""
        return LegGeometry.from_lengths(self.design.lengths)

    # -- what the robot is, as the analyses ask it ------------------------------------------

    @property
    def own_legs(self) -> dict[str, LegGeometry] | None:
        """Each leg's own general leg, by name, where the legs are not the design's.

        ``None`` here: every leg is the paper's leg of the design's l1, l2, l3 within its
        stance limits, so the closed forms on the design's lengths hold for every leg
        (a robot file's legs are each their own: offsets and bends as drawn, its limits).
        """
        return None

    @property
    def stance_limits(self) -> JointLimits | None:
        """The limits that hold a standing leg over the URDF's: the design's (§6).

        ``None`` where each leg's own joint limits hold it standing too (a robot file's).
        """
        return self.design.stance_limits

    @property
    def own_default_gait(self) -> bool:
        """Whether its default gait is sized to it (:mod:`hexaleg.gait.defaults`).

        False here: :class:`~hexaleg.gait.spec.Gait`'s defaults are the template's, sized
        for the paper's 1 m leg.
        """
        return False

    @property
    def design_links(self) -> bool:
        """Whether its leg links are built from the design (segments, ``[structure]`` tubes).

        True here: the template renders each segment's link from the design, a tube of
        its ``[structure]`` included, each along x of its joint's frame.
        """
        return True

    @property
    def mirror_symmetric(self) -> bool:
        """Whether the robot is drawn mirror-symmetric left to right, as the templates are.

        The self-collision search then checks one side's pairs and mirrors them.
        """
        return True

    @property
    def total_mass(self) -> float:
        """Mass of the whole robot [kg]: the design's, which the rendered URDF carries."""
        return self.design.total_mass

    @property
    def body_mass(self) -> float:
        """Mass of the body alone [kg]: the design's."""
        return self.design.body_mass

    @property
    def nominal_height(self) -> float:
        """Height of the body frame above the ground at the nominal stance [m]."""
        return float(self.nominal_base_pose().translation[2])

    @property
    def nominal_footholds(self) -> ArrayF:
        """Every foot at the nominal stance, body frame at the origin (6, 3) [m]."""
        return self.design.nominal_footholds

    @property
    def missing_meshes(self) -> tuple[str, ...]:
        """Visual mesh references whose files were not found: none, the templates draw none."""
        return ()

    def missing_meshes_note(self, what: str) -> str | None:
        """One sentence on the visual meshes not found (``what`` that means); ``None``: none."""
        return None

    def contact_radius(self, leg: str) -> float:
        """Radius of the sphere ``leg``'s foot touches the ground with [m]: the URDF's foot's."""
        link = ET.fromstring(self.urdf).find(
            f"link[@name='{foot_frame_name(self._leg(leg).name)}']"
        )
        sphere = None if link is None else link.find("visual/geometry/sphere")
        if sphere is None:
            raise ModelError(f"the URDF has no foot sphere for leg {leg!r}")
        return float(sphere.attrib["radius"])

    @property
    def simulation_urdf(self) -> str:
        """The URDF a physics simulator loads: this one, its primitive shapes touching."""
        return self.urdf

    @property
    def simulation_draws_links(self) -> bool:
        """Whether the simulated robot has its links' shapes, so that a render shows it."""
        return True

    @property
    def data(self) -> pin.Data:
        """Pinocchio workspace for ``model`` (created on first use: sweeps derive many models)."""
        if self._data is None:
            self._data = self.model.createData()
        return self._data

    @property
    def urdf(self) -> str:
        """The rendered URDF text (rendered on first use for a :meth:`with_design` copy)."""
        if self._urdf is None:
            self._urdf = render_hexapod(self.design)
        return self._urdf

    def collision_model(self) -> pin.GeometryModel:
        """A copy of the URDF's collision geometry (body and links), parsed once per model."""
        if self._collision is None:
            self._collision = pin.buildGeomFromUrdfString(
                self.model, self.urdf, pin.GeometryType.COLLISION
            )
        return self._collision.copy()

    def visual_model(self) -> pin.GeometryModel:
        """The URDF's visual geometry, what a viewer draws (parsed on each call)."""
        return pin.buildGeomFromUrdfString(self.model, self.urdf, pin.GeometryType.VISUAL)

    def with_design(self, design: HexapodDesign) -> HexapodModel:
        """The model of ``design``, whose segments, ratings or posture differ, without Xacro.

        The fast path of sweeps: joint placements, the foot frames, the links' inertias
        (:func:`~hexaleg.robot.inertia.leg_inertials`, as the URDF receives them; the tibia
        carries its foot, as Pinocchio merges a fixed joint's child) and the effort and
        velocity limits are set as the URDF sets them (the nominal posture is not in the
        URDF); the tests prove the result equal to ``HexapodModel(design)``. Every other
        field must be this model's design's.
        """
        if any(
            getattr(self.design, f.name) != getattr(design, f.name)
            for f in fields(design)
            if f.name not in DERIVED_FIELDS
        ):
            raise ModelError(
                "with_design changes only segment lengths, ratings, posture, actuators, battery, "
                "structure"
            )
        model = pin.Model(self.model)
        model.inertias[model.getJointId(ROOT_JOINT)] = pinocchio_inertia(body_inertial(design))
        set_armature(model, [leg.v for leg in self._legs.values()], design)
        links = leg_inertials(design)
        inertias = (
            pinocchio_inertia(links["coxa"]),
            pinocchio_inertia(links["femur"]),
            pinocchio_inertia(links["tibia"]) + pinocchio_inertia(links["foot"], offset=design.l3),
        )
        hip, knee, foot = (pin.SE3(np.eye(3), np.array([x, 0.0, 0.0])) for x in design.lengths)
        for index in self._legs.values():
            model.jointPlacements[index.joints[1]] = hip
            model.jointPlacements[index.joints[2]] = knee
            ratings = as_written(design.rated_torques), as_written(design.rated_speeds)
            for joint, inertia, effort, speed in zip(index.joints, inertias, *ratings, strict=True):
                model.inertias[joint] = inertia
                model.effortLimit[model.idx_vs[joint]] = effort
                model.velocityLimit[model.idx_vs[joint]] = speed
            for frame_id in (index.foot_joint_frame, index.foot_frame):
                frame = model.frames[frame_id]
                frame.placement = foot
                model.frames[frame_id] = frame
        # the same joints and frames: what depends on them only is shared
        return HexapodModel(design, _model=model, _legs=self._legs, _structural=self._structural)

    # -- indices ------------------------------------------------------------------------

    def leg_q_indices(self, leg: str) -> npt.NDArray[np.int_]:
        """Indices of (θ1, θ2, θ3) of ``leg`` in the configuration vector q."""
        return self._leg(leg).q

    def leg_v_indices(self, leg: str) -> npt.NDArray[np.int_]:
        """Indices of (θ1, θ2, θ3) of ``leg`` in the velocity vector v."""
        return self._leg(leg).v

    def leg_joint_ids(self, leg: str) -> tuple[int, int, int]:
        """Pinocchio joint ids of ``leg``'s root, hip and knee joints."""
        root, hip, knee = self._leg(leg).joints
        return root, hip, knee

    def foot_frame_id(self, leg: str) -> int:
        """Pinocchio frame id of the foot of ``leg``."""
        return self._leg(leg).foot_frame

    def root_frame_id(self, leg: str) -> int:
        """Pinocchio frame id of the leg-root frame of ``leg``."""
        return self._leg(leg).root_frame

    def joint_limits(self, leg: str) -> tuple[ArrayF, ArrayF]:
        """(lower, upper) joint limits of ``leg`` read from the URDF [rad]."""
        index = self._leg(leg)
        return index.lower, index.upper

    # -- configurations -----------------------------------------------------------------

    def configuration(
        self,
        base: pin.SE3 | None = None,
        joint_angles: Mapping[str, npt.ArrayLike] | npt.ArrayLike | None = None,
    ) -> ArrayF:
        """Configuration vector q from a base pose and leg joint angles.

        Args:
            base: Body pose in the world frame; identity if omitted.
            joint_angles: Either a mapping leg name → (θ1, θ2, θ3) [rad] or an
                array (6, 3) in ``leg_names`` order; the nominal angles if omitted.

        """
        q = pin.neutral(self.model)
        q[:7] = pin.SE3ToXYZQUAT(base if base is not None else pin.SE3.Identity())
        if joint_angles is None:
            joint_angles = {leg: self.nominal_angles(leg) for leg in self.leg_names}
        if not isinstance(joint_angles, Mapping):
            array = np.asarray(joint_angles, dtype=float).reshape(len(self.leg_names), 3)
            joint_angles = dict(zip(self.leg_names, array, strict=True))
        for leg, angles in joint_angles.items():
            q[self._leg(leg).q] = self.joint_values(leg, angles)
        return q

    def nominal_angles(self, leg: str) -> tuple[float, float, float]:
        """``leg``'s nominal angles (θ1, θ2, θ3) [rad]: the design's, the same on every leg."""
        self._leg(leg)
        return self.design.nominal_angles

    def joint_values(self, leg: str, theta: npt.ArrayLike) -> ArrayF:
        """The model's joint values (..., 3) of ``leg`` at hexaleg's angles θ (..., 3) [rad].

        hexaleg's URDF turns its joints as θ does (q = θ); a robot file's may not.
        """
        self._leg(leg)
        return np.asarray(theta, dtype=float)

    def joint_signs(self, leg: str) -> ArrayF:
        """dq/dθ (3,) of ``leg``'s joints: a model torque times it is the torque on θ."""
        self._leg(leg)
        return np.ones(3)

    def nominal_base_pose(self) -> pin.SE3:
        """Body pose of the nominal stance: level, at the nominal height above the origin."""
        return pin.SE3(np.eye(3), np.array([0.0, 0.0, self.design.nominal_height]))

    def nominal_configuration(self) -> ArrayF:
        """Configuration of the nominal stance: body level, every leg at its nominal angles."""
        return self.configuration(self.nominal_base_pose())

    def joint_angles(self, q: npt.ArrayLike) -> ArrayF:
        """Leg joint angles (6, 3) [rad] from a configuration vector, in ``leg_names`` order."""
        q = np.asarray(q, dtype=float)
        return np.array([self.leg_angles(leg, q[self._legs[leg].q]) for leg in self.leg_names])

    def leg_angles(self, leg: str, values: npt.ArrayLike) -> ArrayF:
        """The angles θ (..., 3) [rad] of ``leg`` at the model's joint values (..., 3)."""
        self._leg(leg)
        return np.asarray(values, dtype=float)

    # -- kinematics ---------------------------------------------------------------------

    def foot_positions(self, q: npt.ArrayLike) -> ArrayF:
        """Foot positions (6, 3) in the world frame [m], in ``leg_names`` order."""
        pin.framesForwardKinematics(self.model, self.data, np.asarray(q, dtype=float))
        return np.array(
            [self.data.oMf[self._legs[leg].foot_frame].translation for leg in self.leg_names]
        )

    def leg_chains(self, q: npt.ArrayLike) -> ArrayF:
        """Every leg's points (6, 4, 3), world frame [m]: its three joints' origins, its foot.

        In ``leg_names`` order; what a drawing of the robot at ``q`` joins with lines.
        """
        pin.framesForwardKinematics(self.model, self.data, np.asarray(q, dtype=float))
        chains = []
        for leg in self.leg_names:
            index = self._legs[leg]
            joints = [self.data.oMi[j].translation for j in index.joints]
            chains.append([*joints, self.data.oMf[index.foot_frame].translation])
        return np.array(chains)

    def root_placements(self) -> dict[str, pin.SE3]:
        """Placement of every leg-root frame in the body frame, read from the model.

        Read without kinematics where each leg-root frame is its root joint's own and that
        joint hangs on the free flyer, as the templates build them (a study's designs then
        need no Pinocchio data).
        """
        joints = {leg: self._legs[leg].joints[0] for leg in self.leg_names}
        if all(self._root_on_flyer(leg) for leg in self.leg_names):
            return {leg: pin.SE3(self.model.jointPlacements[j]) for leg, j in joints.items()}
        pin.framesForwardKinematics(self.model, self.data, pin.neutral(self.model))
        base_inv = self.data.oMf[self.base_frame].inverse()
        return {leg: base_inv * self.data.oMf[self._legs[leg].root_frame] for leg in self.leg_names}

    def _root_on_flyer(self, leg: str) -> bool:
        """Whether ``leg``'s root frame is its root joint's own, on the free-flyer joint."""

        def found() -> bool:
            index = self._legs[leg]
            frame, joint = self.model.frames[index.root_frame], index.joints[0]
            on_flyer = self.model.parents[joint] == self.model.getJointId(ROOT_JOINT)
            own = frame.parentJoint == joint and frame.placement.isIdentity()
            return bool(on_flyer and own)

        return self.structural(f"root on flyer: {leg}", found)

    def structural(self, what: str, make: Callable[[], T]) -> T:
        """``what`` of this model's joints and frames: made by ``make`` the first time.

        Kept for every model :meth:`with_design` derives from the same one (their joints,
        axes and frames are this one's); ``make`` must read nothing else (no length, mass,
        inertia or rating), and the caller must not change what it returns.
        """
        if what not in self._structural:
            self._structural[what] = make()
        found: T = self._structural[what]
        return found

    def foot_jacobian(self, q: npt.ArrayLike, leg: str) -> ArrayF:
        """dp/dv (3, nv) of the foot of ``leg`` in world axes (LOCAL_WORLD_ALIGNED) [m]."""
        jac = pin.computeFrameJacobian(
            self.model,
            self.data,
            np.asarray(q, dtype=float),
            self._leg(leg).foot_frame,
            pin.LOCAL_WORLD_ALIGNED,
        )
        return jac[:3].copy()

    def leg_foot_jacobian(self, q: npt.ArrayLike, leg: str) -> ArrayF:
        """The 3×3 block dp/dθ of ``leg``'s own joints, world axes [m/rad] (eq 20–22)."""
        return self.foot_jacobian(q, leg)[:, self._leg(leg).v]

    def _leg(self, leg: str) -> _LegIndex:
        try:
            return self._legs[leg]
        except KeyError:
            raise ModelError(
                f"no leg named {leg!r}; legs are {', '.join(self.leg_names)}"
            ) from None


def _joint_id(model: pin.Model, name: str) -> int:
    if not model.existJointName(name):
        raise ModelError(f"the model has no joint named {name!r}")
    return int(model.getJointId(name))


def _frame_id(model: pin.Model, name: str) -> int:
    if not model.existFrame(name):
        raise ModelError(f"the model has no frame named {name!r}")
    return int(model.getFrameId(name))
