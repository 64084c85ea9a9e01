"""A robot file's closed chain in Pinocchio on the raw file: the tests' oracle for extremes.

No hexaleg closed form: each foot is a point on its last link (the import's foot point),
posed by Pinocchio's forward kinematics of the file as written, and brought back to its
foothold by Gauss–Newton.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.robot.feet import FootSearch
from hexaleg.robot.imported import import_robot


class RawChain:
    """The raw file in Pinocchio, each foot a point on its last link (the file's own)."""

    def __init__(self, path, offset, shown):
        self.robot = import_robot(path, foot=FootSearch(offset=offset))
        self.model = pin.buildModelFromXML(self.robot.text, pin.JointModelFreeFlyer())
        self.data = self.model.createData()
        self.legs = {leg["name"]: leg for leg in shown["design"]["legs"]}
        # the design's body frame: the roots' mean plane (the design's mounts at z = 0)
        self.plane = np.mean([leg["mount"]["z"] for leg in shown["design"]["legs"]])
        box = shown["robot"]["body_box"]  # the body the extremes stop at, as design show says
        self.half = np.array(box["size"]) / 2

    def joints(self, name):
        """Leg ``name``'s three Pinocchio joints, from the body out."""
        return [self.model.joints[self.model.getJointId(j)] for j in self.legs[name]["joints"]]

    def foot(self, name, q):
        """The foot of leg ``name`` (world) and its Jacobian in the leg's joints."""
        leg = next(r for r in self.robot.legs if r.name == name)
        model, data = self.model, self.data
        pin.computeJointJacobians(model, data, q)
        knee = model.getJointId(leg.joint_names[2])
        link = model.frames[model.getFrameId(leg.chain.segments[2][0])].placement
        point = data.oMi[knee] * link * pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
        jac = pin.getJointJacobian(model, data, knee, pin.LOCAL_WORLD_ALIGNED)
        arm = point.translation - data.oMi[knee].translation
        linear = jac[:3] - pin.skew(arm) @ jac[3:]
        return point.translation.copy(), linear[:, [j.idx_v for j in self.joints(name)]]

    def standing(self, stance):
        """The nominal body height [m] and each stance foot's foothold (world) [m].

        The file's nominal joint values, the body level at the height that puts the
        feet, on average, on the ground.
        """
        nominal = {name: leg["nominal"]["urdf_joint_angles"] for name, leg in self.legs.items()}
        q0 = self.configuration(pin.SE3.Identity(), nominal)
        feet = {name: self.foot(name, q0)[0] for name in stance}
        height = -np.mean([f[2] for f in feet.values()])
        return height, {name: f + np.array([0.0, 0.0, height]) for name, f in feet.items()}

    def configuration(self, body, angles):
        """q with the design's body frame at ``body`` and each leg's file values ``angles``."""
        q = pin.neutral(self.model)
        root = body * pin.SE3(np.eye(3), np.array([0.0, 0.0, -self.plane]))
        q[:7] = pin.SE3ToXYZQUAT(root)
        for name, values in angles.items():
            for joint, value in zip(self.joints(name), values, strict=True):
                q[joint.idx_q] = value
        return q

    def solve(self, q, name, target):
        """Gauss–Newton on leg ``name``'s joints to put its foot at ``target``: (q, residual)."""
        q = q.copy()
        columns = [j.idx_q for j in self.joints(name)]
        for _ in range(100):
            foot, jac = self.foot(name, q)
            error = target - foot
            if np.linalg.norm(error) < 1e-13:
                break
            q[columns] += np.linalg.lstsq(jac, error, rcond=None)[0]
        return q, float(np.linalg.norm(target - self.foot(name, q)[0]))

    def broken(self, q, name, target):
        """What the closed chain breaks for leg ``name`` at q: reach, joint, or nothing."""
        q, residual = self.solve(q, name, target)
        if residual > 1e-9:
            return "reach", q
        leg = self.legs[name]
        values = np.array([q[j.idx_q] for j in self.joints(name)])
        lower, upper = (
            np.asarray(leg["file_limits"]["lower"]),
            np.asarray(leg["file_limits"]["upper"]),
        )
        if np.any(values < lower - 1e-9) or np.any(values > upper + 1e-9):
            return "joint", q
        return None, q

    def clearance(self, body):
        """The design's body box's lowest point above the ground [m]."""
        return body.translation[2] - np.abs(body.rotation[2]) @ self.half


def body_pose(pose, height):
    """The body at displacement ``pose`` (x, y, z [m], roll, pitch, yaw [rad]) from nominal."""
    return pin.SE3(pin.rpy.rpyToMatrix(*pose[3:]), np.array([pose[0], pose[1], pose[2] + height]))
