"""A design's actuators and battery: read from its file, written back, and in its mass."""

from __future__ import annotations

import json

import pytest
from conftest import run_cli

from hexaleg import HexapodDesign
from hexaleg.actuator_catalog import shipped_catalog
from hexaleg.actuators import Actuator, Actuators
from hexaleg.battery import Battery
from hexaleg.design import DEFAULT_RATED_SPEEDS, DEFAULT_RATED_TORQUES
from hexaleg.design_file import design_from_mapping, load_design
from hexaleg.design_text import design_toml

FILE = """
l1 = 0.2
[actuators.root]
catalog = "hd_cha_17a_e_100"
[actuators.hip]
catalog = "hd_cha_25a_100"
[actuators.knee]
catalog = "hd_cha_20a_100"
mass = 2.0
[battery]
capacity = 500
specific_energy = 200
battery_at = [0, 0, 0.05]
regeneration = 0.25
voltage = 48
"""


def motors() -> Actuators:
    """Three actuators written out: no catalog."""
    keys = dict(torque_constant=0.1, resistance=0.4, gearbox_efficiency=0.9, voltage=48.0)
    return Actuators(
        Actuator(50.0, peak_torque=60.0, continuous_torque=20.0, mass=1.0, **keys),
        Actuator(100.0, peak_torque=160.0, continuous_torque=60.0, mass=2.5, **keys),
        Actuator(80.0, peak_torque=120.0, continuous_torque=45.0, mass=1.5, **keys),
    )


def test_the_files_tables_are_the_catalogs_entries_with_their_overrides(tmp_path):
    path = tmp_path / "robot.toml"
    path.write_text(FILE)
    design = load_design(path)
    catalog = shipped_catalog()
    root, hip, knee = (
        catalog.entry(n) for n in ("hd_cha_17a_e_100", "hd_cha_25a_100", "hd_cha_20a_100")
    )
    assert design.actuators is not None and design.battery is not None
    assert design.actuators.root == root.actuator
    assert design.actuators.hip == hip.actuator
    assert design.actuators.knee.mass == 2.0
    assert design.actuators.knee.peak_torque == knee.values["peak_torque"]
    assert design.rated_torques == (
        root.values["peak_torque"],
        hip.values["peak_torque"],
        knee.values["peak_torque"],
    )
    assert design.rated_speeds == tuple(a.rated_speed for a in design.actuators.joints)
    assert design.battery == Battery(500.0, 200.0, (0.0, 0.0, 0.05), 0.25, voltage=48.0)
    assert design.bus_voltage == 48.0  # the battery's, fed to every motor


def test_a_design_without_them_keeps_its_rated_torques_and_speeds():
    design = design_from_mapping({"rated_torques": [10, 20, 30]})
    assert design.actuators is None and design.battery is None
    assert design.rated_torques == (10.0, 20.0, 30.0)
    assert HexapodDesign().rated_torques == DEFAULT_RATED_TORQUES
    assert HexapodDesign().rated_speeds == DEFAULT_RATED_SPEEDS


@pytest.mark.parametrize("catalogued", [True, False])
def test_toml_and_json_read_back_the_same_design(tmp_path, catalogued):
    if catalogued:
        (tmp_path / "in.toml").write_text(FILE)
        design = load_design(tmp_path / "in.toml")
    else:
        design = HexapodDesign(actuators=motors(), battery=Battery(100.0, 150.0))
    (tmp_path / "robot.toml").write_text(design_toml(design))
    assert load_design(tmp_path / "robot.toml") == design
    (tmp_path / "robot.json").write_text(json.dumps({"design": design.as_dict()}))
    assert load_design(tmp_path / "robot.json") == design


def test_the_whole_robots_mass_holds_the_motors_and_the_battery():
    bare = HexapodDesign()
    design = HexapodDesign(actuators=motors(), battery=Battery(300.0, 150.0))
    assert design.total_mass == pytest.approx(bare.total_mass + 6 * (1.0 + 2.5 + 1.5) + 2.0)


@pytest.mark.parametrize(
    ("text", "fragments"),
    [
        ('[actuators.hip]\ncatalog = "hd_cha_25a_100"\n', ["actuators.root", "missing"]),
        (
            FILE.replace("mass = 2.0", "gear_ratoi = 3"),
            ["line 9", "actuators.knee.gear_ratoi", "gear_ratio"],
        ),
        (FILE.replace("capacity = 500", "capacity = -5"), ["battery.capacity", "[0.001"]),
        (FILE.replace("l1 = 0.2", "rated_torques = [1, 2, 3]"), ["rated_torques", "[actuators]"]),
        (FILE.replace('"hd_cha_25a_100"', '"hd_cha_25a_10"'), ["actuators.hip.catalog"]),
        (FILE.replace("voltage = 48", "voltage = 0"), ["battery.voltage", "[0.1"]),
        (  # one bus: 48 V and 680 V motors need the battery's voltage
            FILE.replace("voltage = 48", ""),
            ["battery.voltage", "root 48 V, hip 680 V, knee 680 V"],
        ),
    ],
)
def test_bad_tables_are_one_line_and_exit_2(tmp_path, capsys, text, fragments):
    path = tmp_path / "robot.toml"
    path.write_text(text)
    assert run_cli(["loads", "--design", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err
    for fragment in fragments:
        assert fragment in err


def urdf_masses(xml: str) -> float:
    """Every link's mass in a URDF, summed [kg]."""
    import xml.etree.ElementTree as ET

    return sum(float(m.attrib["value"]) for m in ET.fromstring(xml).iter("mass"))


def test_the_urdf_weighs_exactly_the_motors_and_the_battery_more():
    from hexaleg.robot.urdf import render_hexapod

    bare, battery = HexapodDesign(), Battery(300.0, 150.0, (0.1, -0.05, 0.02))
    design = HexapodDesign(actuators=motors(), battery=battery)
    added = urdf_masses(render_hexapod(design)) - urdf_masses(render_hexapod(bare))
    assert added == pytest.approx(6 * (1.0 + 2.5 + 1.5) + 300.0 / 150.0, rel=1e-12)


def test_each_mass_sits_at_its_joint_in_the_centre_of_mass():
    import math

    import numpy as np
    import pinocchio as pin

    from hexaleg import HexapodModel

    angles = (0.3, 0.25, -1.4)
    bare = HexapodDesign(nominal_angles=angles)
    design = bare.replace(actuators=motors(), battery=Battery(300.0, 150.0, (0.1, -0.05, 0.02)))
    bare_model, model = HexapodModel(bare), HexapodModel(design)
    q = model.nominal_configuration()
    assert np.allclose(q, bare_model.nominal_configuration())
    base = model.nominal_base_pose().translation
    moment = pin.computeTotalMass(bare_model.model) * pin.centerOfMass(
        bare_model.model, bare_model.data, q
    )
    mass = pin.computeTotalMass(bare_model.model)
    theta1, theta2, _ = angles
    # the root motor at the mount, the hip's at the coxa's end, the knee's past the femur
    for mount in design.legs:
        root = base + np.array([mount.x, mount.y, mount.z])
        heading = np.array([math.cos(mount.yaw + theta1), math.sin(mount.yaw + theta1), 0.0])
        hip = root + bare.l1 * heading
        knee = hip + bare.l2 * (math.cos(theta2) * heading + [0.0, 0.0, math.sin(theta2)])
        for point_mass, where in ((1.0, root), (2.5, hip), (1.5, knee)):
            moment, mass = moment + point_mass * where, mass + point_mass
    moment, mass = moment + 2.0 * (base + np.array([0.1, -0.05, 0.02])), mass + 2.0
    assert pin.computeTotalMass(model.model) == pytest.approx(mass, rel=1e-12)
    assert pin.computeTotalMass(model.model) == pytest.approx(design.total_mass, rel=1e-12)
    com = pin.centerOfMass(model.model, model.data, q)
    assert np.allclose(com, moment / mass, rtol=0, atol=1e-12)


def test_armature_adds_n2j_times_the_joints_acceleration():
    import dataclasses

    import numpy as np
    import pinocchio as pin

    from hexaleg import HexapodModel

    spun = Actuators(
        *(
            dataclasses.replace(a, rotor_inertia=j)
            for a, j in zip(motors().joints, (2e-5, 5e-5, 3e-5), strict=True)
        )
    )
    plain, turning = (HexapodModel(HexapodDesign(actuators=a)) for a in (motors(), spun))
    rng = np.random.default_rng(7)
    q = plain.configuration(joint_angles=rng.uniform(-0.5, 0.5, (6, 3)))
    v, a = rng.normal(size=plain.model.nv), rng.normal(size=plain.model.nv)
    step = 1e-3

    def slopes(model: HexapodModel, j: int) -> np.ndarray:  # dτ/dq̈_j by central differences
        ahead, back = a.copy(), a.copy()
        ahead[j] += step
        back[j] -= step
        up = pin.rnea(model.model, model.data, q, v, ahead).copy()
        down = pin.rnea(model.model, model.data, q, v, back).copy()
        return (up - down) / (2 * step)

    for leg in plain.leg_names:
        for joint, j in enumerate(plain.leg_v_indices(leg)):
            added = slopes(turning, j) - slopes(plain, j)
            expected = np.zeros(plain.model.nv)
            expected[j] = spun.joints[joint].gear_ratio ** 2 * spun.joints[joint].rotor_inertia
            assert np.allclose(added, expected, rtol=0, atol=1e-9)
    fast = HexapodModel(HexapodDesign()).with_design(turning.design)
    assert np.array_equal(fast.model.armature, turning.model.armature)
    for mine, theirs in zip(fast.model.inertias, turning.model.inertias, strict=True):
        assert np.allclose(mine.toDynamicParameters(), theirs.toDynamicParameters(), atol=1e-12)


def test_mujoco_sees_the_same_masses_and_armature():
    pytest.importorskip("mujoco")
    import dataclasses

    import numpy as np

    from hexaleg import HexapodModel
    from hexaleg.sim.model import SimModel

    spun = Actuators(*(dataclasses.replace(a, rotor_inertia=4e-5) for a in motors().joints))
    design = HexapodDesign(actuators=spun, battery=Battery(300.0, 150.0))
    sim = SimModel(HexapodModel(design))
    assert sim.mj.body_mass.sum() == pytest.approx(design.total_mass, rel=1e-12)
    expected = np.array([a.gear_ratio**2 * 4e-5 for a in spun.joints])
    assert np.allclose(sim.mj.dof_armature[sim.dof], np.broadcast_to(expected, sim.dof.shape))
