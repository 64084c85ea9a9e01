"""The [structure] table: tubes, their mass and inertia in the URDF and the fast path, bad input."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET

import numpy as np
import pinocchio as pin
import pytest

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.cli.main import main
from hexaleg.design import FOOT_MASS
from hexaleg.design_file import load_design
from hexaleg.design_text import design_toml
from hexaleg.exceptions import ParameterError
from hexaleg.leg_structure import Structure, Tube
from hexaleg.materials import shipped_materials

STEEL = shipped_materials().material("steel_s355")
ALUMINIUM = shipped_materials().material("aluminium_6061_t6")


def tube_oracle(density, outer, wall, length):
    """Mass, centre and inertia about the centre of a uniform tube along x (closed forms)."""
    r_out, r_in = outer / 2, outer / 2 - wall
    mass = density * math.pi * (r_out**2 - r_in**2) * length  # ρ·π/4·(D² − (D − 2t)²)·l
    axial = mass * (r_out**2 + r_in**2) / 2
    across = mass * (3 * (r_out**2 + r_in**2) + length**2) / 12
    return mass, length / 2, np.diag([axial, across, across])


def random_structured(seed, material=ALUMINIUM):
    rng = np.random.default_rng(seed)
    lengths = rng.uniform(0.1, 0.5, 3)
    tubes = []
    for _ in range(3):
        outer = rng.uniform(0.01, 0.06)
        tubes.append(Tube(outer, rng.choice([rng.uniform(0.0005, outer / 2), outer / 2])))
    return HexapodDesign(
        l1=lengths[0], l2=lengths[1], l3=lengths[2], structure=Structure(material, *tubes)
    )


def test_a_tube_s_area_and_second_moment_are_the_annulus_closed_forms():
    tube = Tube(0.04, 0.003)
    assert tube.area == pytest.approx(math.pi * (0.02**2 - 0.017**2), rel=1e-14)
    assert tube.second_moment == pytest.approx(math.pi / 4 * (0.02**4 - 0.017**4), rel=1e-14)
    rod = Tube(0.02, 0.01)  # the wall reaches half the diameter: a solid rod
    assert rod.inner_diameter == 0 and rod.area == pytest.approx(math.pi * 0.01**2, rel=1e-14)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_the_urdf_link_inertials_are_the_tubes_closed_forms(seed):
    """Each segment's <inertial> in the URDF text, against the tube formulas written here."""
    design = random_structured(seed)
    root = ET.fromstring(HexapodModel(design).urdf)
    links = {link.get("name"): link for link in root.iter("link")}
    for segment, length, tube in zip(
        ("coxa", "femur"), design.lengths, design.structure.tubes, strict=False
    ):
        inertial = links[f"lf_{segment}"].find("inertial")
        mass, com, tensor = tube_oracle(ALUMINIUM.density, tube.outer_diameter, tube.wall, length)
        assert float(inertial.find("mass").get("value")) == pytest.approx(mass, rel=1e-12)
        origin = [float(v) for v in inertial.find("origin").get("xyz").split()]
        assert origin == pytest.approx([com, 0, 0], abs=1e-15)
        got = inertial.find("inertia")
        moments = [float(got.get(k)) for k in ("ixx", "iyy", "izz")]
        assert moments == pytest.approx(list(np.diag(tensor)), rel=1e-12)
    # the drawn cylinder is the tube's outside
    cylinder = links["lf_tibia"].find("visual/geometry/cylinder")
    assert float(cylinder.get("radius")) == pytest.approx(design.structure.tibia.outer_diameter / 2)


@pytest.mark.parametrize("seed", [4, 5])
def test_the_model_carries_the_tubes_with_its_foot_and_actuator_points(seed):
    """Pinocchio's inertias from the URDF: tube, plus the foot on the tibia (parallel axes)."""
    design = random_structured(seed, STEEL)
    model = HexapodModel(design).model
    knee = model.getJointId("rm_knee_joint")
    l3, tube = design.l3, design.structure.tibia
    mass, com, tensor = tube_oracle(STEEL.density, tube.outer_diameter, tube.wall, l3)
    total = mass + FOOT_MASS
    centre = (mass * com + FOOT_MASS * l3) / total
    foot = 0.4 * FOOT_MASS * design.link_radius**2 * np.eye(3)
    shift = np.diag([0.0, 1.0, 1.0]) * (mass * (com - centre) ** 2 + FOOT_MASS * (l3 - centre) ** 2)
    inertia = model.inertias[knee]
    assert inertia.mass == pytest.approx(total, rel=1e-13)
    assert inertia.lever == pytest.approx([centre, 0, 0], rel=1e-12)
    np.testing.assert_allclose(inertia.inertia, tensor + foot + shift, rtol=1e-10, atol=1e-18)


@pytest.mark.parametrize("seed", [6, pytest.param(7, marks=pytest.mark.slow), 8])
def test_with_design_equals_the_model_built_from_the_urdf(seed):
    design = random_structured(seed, STEEL)
    fast = HexapodModel(HexapodDesign(l1=0.3)).with_design(design)
    slow = HexapodModel(design)
    for i in range(1, slow.model.njoints):
        a, b = fast.model.inertias[i], slow.model.inertias[i]
        assert a.mass == pytest.approx(b.mass, rel=1e-12)
        np.testing.assert_allclose(a.lever, b.lever, atol=1e-13)
        np.testing.assert_allclose(a.inertia, b.inertia, atol=1e-13)
    assert pin.computeTotalMass(slow.model) == pytest.approx(design.total_mass, rel=1e-12)


def test_total_mass_has_the_tubes_in_place_of_the_linear_density():
    tube = Tube(0.03, 0.002)
    design = HexapodDesign(structure=Structure(ALUMINIUM, tube, tube, tube))
    legs = 6 * (ALUMINIUM.density * tube.area * design.leg_length + FOOT_MASS)
    assert design.total_mass == pytest.approx(design.body_mass + legs, rel=1e-13)
    assert HexapodDesign().total_mass == pytest.approx(60 + 6 * (4.0 + FOOT_MASS))


def test_size_without_tubes_keeps_the_linear_density_until_sized():
    design = HexapodDesign(structure=Structure(ALUMINIUM, size=True))
    assert design.total_mass == pytest.approx(HexapodDesign().total_mass)


def test_a_design_file_s_structure_reads_back_from_what_hexaleg_writes(tmp_path):
    own = {"density": 1200.0, "youngs_modulus": 3e9, "yield_strength": 5e7, "source": "mine"}
    for material in ("steel_s355", own):
        path = tmp_path / "d.toml"
        path.write_text(
            f"[structure]\nmaterial = {_toml(material)}\nsafety_factor = 1.5\n"
            "deflection_limit = 0.004\n"
            "coxa = { outer_diameter = 0.04, wall = 0.002 }\n"
            "femur = { outer_diameter = 0.05, wall = 0.025 }\n"
            "tibia = { outer_diameter = 0.03, wall = 0.0015 }\n",
            encoding="utf-8",
        )
        design = load_design(path)
        assert design.structure.safety_factor == 1.5
        assert design.structure.femur == Tube(0.05, 0.025)
        again = tmp_path / "again.toml"
        again.write_text(design_toml(design), encoding="utf-8")
        assert load_design(again) == design


def _toml(value):
    if isinstance(value, str):
        return f'"{value}"'
    return "{ " + ", ".join(f"{k} = {v!r}" for k, v in value.items()).replace("'", '"') + " }"


BAD = [
    ("coxa = { outer_diameter = 0.04, wall = 0.0 }", "structure.coxa.wall = 0 ", "[m]"),
    ("coxa = { outer_diameter = 0.04, wall = 0.03 }", "structure.coxa.wall = 0.03 ", "0.02]"),
    ("coxa = { outer_diameter = -0.04, wall = 0.002 }", "structure.coxa.outer_diameter", "[m]"),
    ("safety_factor = 0.5", "structure.safety_factor = 0.5 ", "[1, 100]"),
    ('material = "aluminum_6061"', "structure.material = 'aluminum_6061'", "aluminium_6061_t6"),
    (
        "material = { density = 2700, youngs_modulus = 7e10, yield_strength = -1e8 }",
        "structure.material.yield_strength",
        "[Pa]",
    ),
    ("femur = { outer_diameter = 0.04 }", "structure.femur.wall is missing", "[m]"),
    ("siz = true", "unknown key 'structure.siz'", "did you mean 'size'"),
]


@pytest.mark.parametrize(("line", "field", "allowed"), BAD)
def test_bad_structure_input_is_one_line_exit_2_and_nothing_written(
    tmp_path, capsys, line, field, allowed
):
    lines = {
        "material": 'material = "aluminium_6061_t6"',
        "coxa": "coxa = { outer_diameter = 0.04, wall = 0.002 }",
        "femur": "femur = { outer_diameter = 0.04, wall = 0.002 }",
        "tibia": "tibia = { outer_diameter = 0.03, wall = 0.002 }",
    }
    lines[line.split(" =")[0] if line.split(" =")[0] in lines else "extra"] = line
    path = tmp_path / "bad.toml"
    path.write_text("[structure]\n" + "\n".join(lines.values()) + "\n", encoding="utf-8")
    out = tmp_path / "robot.urdf"
    assert main(["urdf", "--design", str(path), "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and field in err and allowed in err, err
    assert not out.exists()


def test_a_missing_tube_without_size_names_the_segment():
    with pytest.raises(ParameterError, match=r"tibia .* size = true"):
        Structure(ALUMINIUM, Tube(0.04, 0.002), Tube(0.04, 0.002))


def test_design_init_writes_a_commented_structure_and_show_prints_the_tubes(tmp_path, capsys):
    path = tmp_path / "new.toml"
    assert main(["design", "init", str(path)]) == 0
    text = path.read_text(encoding="utf-8")
    assert "# [structure]" in text and '# material = "aluminium_6061_t6"' in text
    uncommented = text.replace("# [structure", "[structure").replace("# material =", "material =")
    for key in ("safety_factor", "deflection_limit", "size", "outer_diameter", "wall"):
        uncommented = uncommented.replace(f"# {key} =", f"{key} =")
    path.write_text(uncommented, encoding="utf-8")
    capsys.readouterr()
    assert main(["design", "show", "--design", str(path)]) == 0
    shown = capsys.readouterr().out
    assert "aluminium_6061_t6" in shown and "coxa tube" in shown and "D 40 mm, wall 2 mm" in shown
