"""Real public hexapod descriptions imported, each leg's numbers derived by hand from the file."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from robot_files import draw_hexapod

from hexaleg.exceptions import RobotImportError, RobotImportWarning
from hexaleg.kinematics import foot_jacobian, foot_position
from hexaleg.robot.chains import find_chains
from hexaleg.robot.description import parse_urdf
from hexaleg.robot.feet import FootSearch, find_foot
from hexaleg.robot.imported import import_robot, robot_from_text
from hexaleg.robot.source import read_robot_text

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = ROBOTS / "kraby" / "hexapod.urdf"
OCHS = ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro"
HUMA = ROBOTS / "phantomx_humarobotics" / "urdf" / "phantomx.xacro"
HUMA_PACKAGES = {"phantomx_description": ROBOTS / "phantomx_humarobotics"}


def _dimensions(leg):
    g = leg.reading.geometry
    return (g.coxa, g.hip_height, g.femur, g.tibia, g.foot_lateral)


def test_kraby_legs_by_hand():
    robot = import_robot(KRABY)
    # joint_0 → servomotor_1 at x = 0.049 on the yaw axis' perpendicular; the knee sits
    # 0.0495 + 0.0107 from the hip along servomotor_1's y (a fixed joint between);
    # the endcap 0.088 along foot_i's y; every offset lies in the leg plane
    for leg in robot.legs:
        np.testing.assert_allclose(
            _dimensions(leg), (0.049, 0, 0.0495 + 0.0107, 0.088, 0), atol=1e-12
        )
        assert leg.reading.foot.rule == "frame"
        assert leg.reading.foot.source.startswith("link endcap_")
        # servomotor_1's rpy (π/2, −π/4, 0) drops the femur 45°; foot_i's Rz(−π/4) after the
        # fixed Rz(π) turns the tibia a further 45°: θ = (0, −π/4, −π/4) at q = 0
        theta0 = leg.reading.joint_map.from_file(np.zeros(3))
        np.testing.assert_allclose(theta0, (0, -math.pi / 4, -math.pi / 4), atol=1e-12)
        lower, upper = leg.file_limits
        np.testing.assert_allclose((lower, upper), ([-1.57] * 3, [1.57] * 3))
        assert leg.ratings == ((1.18,) * 3, (6.308,) * 3)
    # servomotor_0 is on the box's front right, at yaw −45°: hexaleg's "rf"
    rf = robot.legs[robot.leg_names.index("rf")]
    assert rf.joint_names == ("servomotor_0", "servomotor_1", "servomotor_2")
    assert rf.reading.mount_yaw == pytest.approx(-0.78539, abs=1e-12)


def test_kevin_ochs_phantomx_by_hand():
    robot = import_robot(OCHS, foot=FootSearch(offset=(0.0, 0.133, 0.0)))
    # coxa_length 0.052 along the coxa's x, femur_length 0.065 along the femur's −y; the
    # foot given on the tibia's +y, which continues the femur line (tibia = Rx(π) femur)
    for leg in robot.legs:
        np.testing.assert_allclose(_dimensions(leg), (0.052, 0, 0.065, 0.133, 0), atol=1e-12)
        np.testing.assert_allclose(leg.reading.joint_map.from_file(np.zeros(3)), 0, atol=1e-12)
        assert leg.reading.foot.rule == "foot_offset"
        # the right legs' yaw axes are written 0 0 -1: hexaleg's θ1 is the file's −q1
        assert leg.reading.joint_map.signs[0] == (1 if leg.name[0] == "l" else -1)
    assert robot.legs[0].joint_names == ("coxa_joint_LF", "femur_joint_LF", "tibia_joint_LF")
    assert "head_pan_link" in robot.body and "head_tilt_link" in robot.body  # locked head


def test_humarobotics_phantomx_by_hand():
    # its leg links give ixx 0.0051, iyy 0.0082, izz 0.0011 kg·m² with small products:
    # iyy > ixx + izz, which no rigid body has: warned about, used as given
    with pytest.warns(RobotImportWarning, match=r"links c1_lf, c2_lf, thigh_lf, tibia_lf and"):
        robot = import_robot(HUMA, packages=HUMA_PACKAGES, foot=FootSearch(offset=(0, -0.1, 0)))
    # coxa 0.054 (c2 fixed at y −0.054); the knee at thigh (0, −0.0645, −0.0145): the femur
    # is their hypotenuse, 14.5 mm below the hip line, θ2 = −atan(14.5/64.5) at q = 0.
    # The file's rounded angles (4.7123, 1.5704) tilt the axes ≲ 4e-4 rad: 1e-4 m slack.
    femur = math.hypot(0.0645, 0.0145)
    for leg in robot.legs:
        np.testing.assert_allclose(_dimensions(leg), (0.054, 0, femur, 0.1, 0), atol=1e-4)
        theta0 = leg.reading.joint_map.from_file(np.zeros(3))
        assert theta0[1] == pytest.approx(-math.atan2(0.0145, 0.0645), abs=1e-3)
        assert leg.ratings == ((2.8,) * 3, (5.6548668,) * 3)
    # the file's "lf" legs sit at y < 0 (REP 103's right): hexaleg names legs by position
    assert robot.legs[robot.leg_names.index("rf")].joint_names[0] == "j_c1_lf"


def _without(text: str, start: str, end: str) -> str:
    i = text.index(start)
    return text[:i] + text[text.index(end, i) + len(end) :]


def test_refusals_name_what_was_found():
    text, _ = draw_hexapod(1)
    five = _without(text, '<joint name="leg5_j1"', "</robot>") + "</robot>"
    with pytest.raises(RobotImportError, match=r"^found 5 legs of 3 revolute joints"):
        robot_from_text(five)
    # the yaw axis turned onto the body's x: refused, naming the joint and its axis
    lines = text.split("\n")
    j1 = next(i for i, line in enumerate(lines) if line.startswith('<joint name="leg2_j1"'))
    lines[j1] = lines[j1].replace('<axis xyz="0 0 1"/>', '<axis xyz="1 0 0"/>')
    lines[j1] = lines[j1].replace('<axis xyz="0 0 -1"/>', '<axis xyz="1 0 0"/>')
    with pytest.raises(RobotImportError, match=r"joint leg2_j1's axis .* from the body's vertical"):
        robot_from_text("\n".join(lines))
    lines = text.split("\n")
    j3 = next(i for i, line in enumerate(lines) if line.startswith('<joint name="leg3_j3"'))
    lines[j3] = lines[j3].replace('<axis xyz="0 0 1"/>', '<axis xyz="0 1 0"/>')
    lines[j3] = lines[j3].replace('<axis xyz="0 0 -1"/>', '<axis xyz="0 1 0"/>')
    with pytest.raises(RobotImportError, match=r"joint leg3_j2's axis .* not parallel to leg3_j3"):
        robot_from_text("\n".join(lines))


def test_refusals_of_chains_and_feet():
    text, _ = draw_hexapod(2, foot_link=False)
    # no foot link, no collision shapes: refused, naming foot_offset
    with pytest.raises(RobotImportError, match=r"no foot found on link .*give foot_offset X Y Z"):
        robot_from_text(text)
    # a fourth revolute joint on a leg
    extra = (
        '<joint name="leg0_j4" type="revolute"><parent link="leg0_tibia"/><child link="x4"/>'
        '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>'
        '<link name="x4"/></robot>'
    )
    four = text.replace("</robot>", extra)
    with pytest.raises(RobotImportError, match=r"leg from joint leg0_j1 has 4 revolute joints"):
        robot_from_text(four, FootSearch(offset=(0.1, 0, 0)))
    with pytest.raises(RobotImportError, match=r"^\S+ is not XML"):
        robot_from_text("<robot>", source=Path("bad.urdf"))
    with pytest.raises(RobotImportError, match=r"no such file"):
        read_robot_text(ROBOTS / "missing.urdf")


def _collision(origin: str, geometry: str) -> str:
    return f"<collision>{origin}<geometry>{geometry}</geometry></collision>"


def test_foot_rules_sphere_box_and_mm_mesh(tmp_path):
    import trimesh

    text, _ = draw_hexapod(3, foot_link=False)
    # shapes on leg0's tibia (in its frame, knee axis ∥ z): the sphere's centre, the box's
    # far end along its longest side, the mm mesh's vertex farthest from the knee axis
    sphere = _collision('<origin xyz="0.01 0.02 0.03"/>', '<sphere radius="0.01"/>')
    box = _collision('<origin xyz="0.1 0 0"/>', '<box size="0.08 0.01 0.02"/>')
    mesh = trimesh.creation.box(extents=(100.0, 10.0, 10.0))  # millimetres
    mesh.apply_translation((60.0, 0.0, 0.0))
    mesh.export(tmp_path / "tibia.stl")
    scaled = _collision("", '<mesh filename="tibia.stl" scale="0.001 0.001 0.001"/>')
    for shape, rule, point in (
        (sphere, "sphere", (0.01, 0.02, 0.03)),
        (box, "box", (0.14, 0, 0)),
        (scaled, "mesh", (0.11, 0.005, 0.005)),
    ):
        with_shape = text.replace('<link name="leg0_tibia">', f'<link name="leg0_tibia">{shape}')
        search = FootSearch(base_dir=tmp_path)
        description = parse_urdf(with_shape)
        chain = next(c for c in find_chains(description).legs if c.joints[0].name == "leg0_j1")
        foot = find_foot(description, chain, description.frames_at_zero(), search)
        assert foot.rule == rule
        if rule == "mesh":
            assert abs(foot.point[0]) == pytest.approx(0.11, abs=1e-12)
        else:
            np.testing.assert_allclose(foot.point, point, atol=1e-12)


def test_inertia_breaking_the_triangle_inequality_is_warned(recwarn):
    text, _ = draw_hexapod(4)
    robot_from_text(text)
    assert not [w for w in recwarn if issubclass(w.category, RobotImportWarning)]
    start = text.index('<link name="leg2_femur">')
    end = text.index("</inertial>", start)
    bad = 'ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.0025"/>'
    head = text[: text.index("<inertia ", start)] + "<inertia " + bad
    with pytest.warns(RobotImportWarning, match=r"^links leg2_femur have inertias"):
        robot_from_text(head + text[end:])


@pytest.mark.parametrize("layout", ["rectangle", "hexagon"])
def test_the_template_imported_back_equals_its_design(layout):
    from hexaleg import HexapodDesign
    from hexaleg.robot.robot_design import robot_design
    from hexaleg.robot.urdf import render_hexapod

    design = HexapodDesign(l1=0.15, l2=0.35, l3=0.45, layout=layout)
    robot = robot_from_text(render_hexapod(design))
    assert robot.leg_names == design.leg_names
    for leg, mount in zip(robot.legs, design.legs, strict=True):
        g = leg.reading.geometry
        np.testing.assert_allclose(_dimensions(leg), (0.15, 0, 0.35, 0.45, 0), atol=1e-12)
        assert leg.reading.joint_map.signs == (1, 1, 1)
        np.testing.assert_allclose(leg.reading.joint_map.offsets, 0, atol=1e-12)
        np.testing.assert_allclose(
            leg.reading.mount[:3, 3], (mount.x, mount.y, mount.z), atol=1e-12
        )
        assert leg.reading.mount_yaw == pytest.approx(mount.yaw, abs=1e-12)
        assert leg.reading.foot.rule == "frame"
        assert g.lengths == pytest.approx(design.lengths, abs=1e-12)
    back = robot_design(robot, design)
    assert back.lengths == pytest.approx(design.lengths, abs=1e-12)


@pytest.mark.parametrize(("path", "offset"), [(KRABY, None), (OCHS, (0.0, 0.133, 0.0))])
def test_real_robot_fk_and_jacobian_equal_pinocchio(path, offset):
    robot = import_robot(path, foot=FootSearch(offset=offset))
    model = pin.buildModelFromXML(robot.text)
    data = model.createData()
    rng = np.random.default_rng(6)
    for _ in range(5):
        q = rng.uniform(-1.5, 1.5, model.nq)
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        for leg in robot.legs:
            joints = [model.joints[model.getJointId(n)] for n in leg.joint_names]
            theta = leg.reading.joint_map.from_file([q[j.idx_q] for j in joints])
            rotation, origin = leg.reading.mount[:3, :3], leg.reading.mount[:3, 3]
            knee = model.getJointId(leg.joint_names[2])
            placement = pin.SE3(np.eye(3), np.asarray(leg.reading.foot.point))
            body = model.frames[model.getFrameId(leg.chain.segments[2][0])].placement
            foot = data.oMi[knee] * body * placement
            expected = rotation @ foot_position(leg.reading.geometry, theta) + origin
            np.testing.assert_allclose(expected, foot.translation, atol=1e-12)
            jac = pin.getJointJacobian(model, data, knee, pin.LOCAL_WORLD_ALIGNED)
            arm = foot.translation - data.oMi[knee].translation
            linear = jac[:3] - pin.skew(arm) @ jac[3:]  # the foot point's velocity
            columns = linear[:, [j.idx_v for j in joints]]
            closed = rotation @ foot_jacobian(leg.reading.geometry, theta)
            np.testing.assert_allclose(
                closed * leg.reading.joint_map.sign_array, columns, atol=1e-12
            )


def test_a_real_four_joint_leg_is_refused_naming_its_joints():
    golem = ROBOTS / "golem_4dof" / "urdf" / "hexapod_model.xacro"
    expected = (
        r"^leg from joint coxa_joint_\w\w has 4 revolute joints \(coxa_joint_\w\w, "
        r"femur_joint_\w\w, tibia_joint_\w\w, tarsus_joint_\w\w\); a yaw-pitch-pitch leg has 3 "
        r"\(--lock-joint NAME holds one at its zero\)$"
    )
    with pytest.raises(RobotImportError, match=expected):
        import_robot(golem)
