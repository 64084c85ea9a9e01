"""The rendered URDF: valid, loadable by yourdfpy and Pinocchio, and the same robot in both."""

from __future__ import annotations

import io
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest
import yourdfpy
from conftest import random_designs

from hexaleg import HexapodDesign, HexapodModel, render_hexapod, render_leg, write_urdf
from hexaleg.exceptions import TemplateError
from hexaleg.robot.urdf import template_dir, validate_urdf


def _yourdfpy(xml: str) -> yourdfpy.URDF:
    return yourdfpy.URDF.load(io.BytesIO(xml.encode()), load_meshes=False)


@pytest.mark.parametrize("design", [HexapodDesign(), *random_designs(3, seed=11)])
def test_yourdfpy_and_pinocchio_agree_on_every_foot(design):
    model = HexapodModel(design)
    robot = _yourdfpy(model.urdf)
    rng = np.random.default_rng(12)
    for _ in range(5):
        angles = rng.uniform(-1.0, 1.0, size=(6, 3))
        cfg = {
            f"{leg}_{joint}_joint": angles[i, j]
            for i, leg in enumerate(model.leg_names)
            for j, joint in enumerate(("root", "hip", "knee"))
        }
        robot.update_cfg(cfg)
        feet = model.foot_positions(model.configuration(pin.SE3.Identity(), angles))
        for i, leg in enumerate(model.leg_names):
            transform = robot.get_transform(f"{leg}_foot", "base_link")
            np.testing.assert_allclose(transform[:3, 3], feet[i], atol=1e-12)


def test_nominal_stance_feet_on_ground_and_body_level(hexapod_model, default_design):
    q = hexapod_model.nominal_configuration()
    feet = hexapod_model.foot_positions(q)
    np.testing.assert_allclose(feet[:, 2], 0.0, atol=1e-12)
    pin.framesForwardKinematics(hexapod_model.model, hexapod_model.data, q)
    body = hexapod_model.data.oMf[hexapod_model.base_frame]
    np.testing.assert_allclose(body.rotation, np.eye(3), atol=1e-15)
    assert body.translation[2] == pytest.approx(default_design.nominal_height, abs=1e-15)


@pytest.mark.parametrize("design", random_designs(4, seed=13))
def test_nominal_stance_for_random_designs(design):
    model = HexapodModel(design)
    feet = model.foot_positions(model.nominal_configuration())
    np.testing.assert_allclose(feet[:, 2], 0.0, atol=1e-12)


def test_urdf_carries_the_design(default_design):
    root = ET.fromstring(render_hexapod(default_design))
    joints = {j.get("name"): j for j in root.iter("joint")}
    revolute = [n for n, j in joints.items() if j.get("type") == "revolute"]
    assert len(revolute) == 18
    knee = joints["lf_knee_joint"]
    assert knee.find("axis").get("xyz") == "0 -1 0"
    assert float(knee.find("limit").get("lower")) == pytest.approx(
        default_design.joint_range.theta3[0]
    )
    assert knee.find("origin").get("xyz") == f"{default_design.l2!r} 0 0"
    mount = joints["rm_root_joint"].find("origin")
    assert [float(v) for v in mount.get("rpy").split()] == pytest.approx([0, 0, -np.pi / 2])
    body = next(link for link in root.iter("link") if link.get("name") == "base_link")
    assert body.find("visual/geometry/box").get("size").split() == ["1.0", "0.6", "0.1"]


def test_joint_limits_are_read_back_from_the_model(hexapod_model, default_design):
    lower, upper = hexapod_model.joint_limits("lr")
    np.testing.assert_allclose(lower, default_design.joint_range.lower)
    np.testing.assert_allclose(upper, default_design.joint_range.upper)


def test_root_placements_are_the_mounts(hexapod_model, default_design):
    roots = hexapod_model.root_placements()
    for mount in default_design.mounts:
        placement = roots[mount.name]
        np.testing.assert_allclose(placement.translation, mount.position, atol=1e-15)
        np.testing.assert_allclose(
            pin.rpy.matrixToRpy(placement.rotation), [0, 0, mount.yaw], atol=1e-12
        )


def test_single_leg_urdf_has_its_root_at_the_origin(default_design):
    model = pin.buildModelFromXML(render_leg(default_design))
    assert model.nq == 3
    assert model.existFrame("leg_foot")


def test_rendering_is_deterministic_and_machine_independent(default_design):
    first = render_hexapod(default_design)
    assert first == render_hexapod(default_design)
    assert str(template_dir()) not in first


def test_numbers_reach_xacro_exactly():
    design = HexapodDesign(l1=0.1 + 0.2, l2=1 / 3)
    root = ET.fromstring(render_hexapod(design))
    hip = next(j for j in root.iter("joint") if j.get("name") == "lf_hip_joint")
    assert float(hip.find("origin").get("xyz").split()[0]) == design.l1  # bit-exact


def test_invalid_urdf_is_rejected():
    with pytest.raises(TemplateError):
        validate_urdf("<robot name='x'><joint name='j' type='revolute'></robot>")


def test_write_urdf_is_atomic(tmp_path, default_design):
    path = write_urdf(default_design, tmp_path / "sub" / "robot.urdf")
    assert path.read_text() == render_hexapod(default_design)
    assert [p.name for p in path.parent.iterdir()] == ["robot.urdf"]


def test_templates_ship_inside_the_installed_package(tmp_path):
    """A non-editable install finds its templates in the package, not the checkout."""
    import subprocess
    import sys
    from pathlib import Path

    code = (
        "import hexaleg, hexaleg.robot.urdf as u; print(hexaleg.__file__); print(u.template_dir())"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, cwd=tmp_path, timeout=120
    )
    package_file, templates = (Path(line) for line in out.stdout.split())
    package = package_file.parent
    checkout = Path(__file__).resolve().parent.parent
    if package.parent == checkout:  # editable or source-tree import: the checkout's urdf/
        assert templates == checkout / "urdf"
    else:
        assert templates == package / "urdf"
    assert (templates / "leg.xacro").is_file()


def test_urdf_joints_carry_the_rated_torques_and_speeds():
    design = HexapodDesign(rated_torques=(11.0, 22.0, 33.0), rated_speeds=(1.5, 2.5, 3.5))
    root = ET.fromstring(render_hexapod(design))
    expected = {"root": (11.0, 1.5), "hip": (22.0, 2.5), "knee": (33.0, 3.5)}
    seen = 0
    for joint in root.iter("joint"):
        kind = joint.get("name", "").split("_")[-2]
        if joint.get("type") == "revolute":
            limit = joint.find("limit")
            assert (float(limit.get("effort")), float(limit.get("velocity"))) == expected[kind]
            seen += 1
    assert seen == 18


def _solid_cylinder_about_its_centre(mass, radius, length):
    """Oracle: a solid cylinder along x, principal moments about its centre [kg·m²]."""
    side = mass * (3 * radius**2 + length**2) / 12
    return np.diag([mass * radius**2 / 2, side, side])


@pytest.mark.parametrize("design", [HexapodDesign(), *random_designs(2, seed=17)])
def test_link_inertias_are_solid_cylinders_and_a_foot_sphere(design):
    """Each leg's inertias in the model read from the URDF, against closed forms here."""
    from hexaleg.design import FOOT_MASS

    model = HexapodModel(design).model
    r, rho = design.link_radius, design.link_linear_density
    root, hip, knee = (model.getJointId(f"rf_{j}_joint") for j in ("root", "hip", "knee"))
    for joint, length, radius in ((root, design.l1, r), (hip, design.l2, r)):
        inertia = model.inertias[joint]
        assert inertia.mass == pytest.approx(rho * length, rel=1e-14)
        np.testing.assert_allclose(inertia.lever, [length / 2, 0, 0], atol=1e-15)
        expected = _solid_cylinder_about_its_centre(rho * length, radius, length)
        np.testing.assert_allclose(inertia.inertia, expected, rtol=1e-12, atol=1e-18)
    # the tibia (radius 0.8 r) carries the foot: a sphere of FOOT_MASS and radius r at l3
    l3, tibia_mass = design.l3, rho * design.l3
    mass = tibia_mass + FOOT_MASS
    com = (tibia_mass * l3 / 2 + FOOT_MASS * l3) / mass
    about_com = _solid_cylinder_about_its_centre(tibia_mass, 0.8 * r, l3) + np.eye(3) * (
        0.4 * FOOT_MASS * r**2
    )
    shift = np.diag([0.0, 1.0, 1.0])  # parallel axes: both centres lie on x
    about_com += shift * (tibia_mass * (l3 / 2 - com) ** 2 + FOOT_MASS * (l3 - com) ** 2)
    knee_inertia = model.inertias[knee]
    assert knee_inertia.mass == pytest.approx(mass, rel=1e-14)
    np.testing.assert_allclose(knee_inertia.lever, [com, 0, 0], rtol=1e-13)
    np.testing.assert_allclose(knee_inertia.inertia, about_com, rtol=1e-10, atol=1e-18)


@pytest.mark.parametrize("layout", ["rectangle", "hexagon"])
def test_body_inertia_is_a_solid_box_or_cylinder(layout):
    design = HexapodDesign(layout=layout, body_mass=42.0, body_height=0.12)
    body = HexapodModel(design).model.inertias[1]  # the free flyer carries base_link
    m, h = 42.0, 0.12
    if layout == "rectangle":
        a, b = design.body_length, design.body_width
        expected = np.diag([b**2 + h**2, a**2 + h**2, a**2 + b**2]) * m / 12
    else:
        r = design.body_radius
        expected = np.diag([(3 * r**2 + h**2) / 12, (3 * r**2 + h**2) / 12, r**2 / 2]) * m
    assert body.mass == pytest.approx(m)
    np.testing.assert_allclose(body.lever, 0.0, atol=1e-15)
    np.testing.assert_allclose(body.inertia, expected, rtol=1e-12)
