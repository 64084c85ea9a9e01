"""Design validation: every bad input is a DesignError naming field, value and range."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg import (
    STANCE_LIMITS,
    DesignError,
    HexapodDesign,
    JointLimits,
    LegMount,
    default_mounts,
    foot_position,
)


def test_defaults_are_the_papers_leg():
    design = HexapodDesign()
    assert design.lengths == (0.2, 0.4, 0.4)
    assert design.leg_length == pytest.approx(1.0)
    assert design.leg_names == ("lf", "lm", "lr", "rf", "rm", "rr")
    assert design.mounts == default_mounts(design.body_length, design.body_width)


def test_nominal_height_puts_feet_on_the_ground():
    design = HexapodDesign()
    foot_z = foot_position(design.lengths, design.nominal_angles)[2]
    assert design.nominal_height + design.mounts[0].z + foot_z == pytest.approx(0.0, abs=1e-15)
    assert design.nominal_height == pytest.approx(design.l3)  # femur level, tibia vertical


@pytest.mark.parametrize(
    ("l1_ratio", "l3_ratio", "total"),
    [(0.05, 0.475, 1.0), (0.2, 0.4, 1.0), (0.1, 0.3, 2.5)],
)
def test_from_ratios(l1_ratio, l3_ratio, total):
    design = HexapodDesign.from_ratios(l1_ratio, l3_ratio, total)
    assert design.l1 == pytest.approx(l1_ratio * total)
    assert design.l3 == pytest.approx(l3_ratio * total)
    assert design.leg_length == pytest.approx(total)


@pytest.mark.parametrize("field", ["l1", "l2", "l3", "body_length", "body_width", "body_height"])
@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf, "abc"])
def test_lengths_must_be_finite_and_positive(field, value):
    if field == "l1" and value == 0.0:
        # a coxa of 0: the hip axis meets the yaw axis, a valid hexapod (the leg of eq 7)
        assert HexapodDesign(l1=0.0).nominal_footholds[0, 0] == pytest.approx(0.5 + 0.4 * 0.5**0.5)
        return
    with pytest.raises(DesignError) as info:
        HexapodDesign(**{field: value})
    assert info.value.field == field
    message = str(info.value)
    assert message.startswith(f"{field} = ")
    assert "[m]" in message or "real number" in message or "finite" in message


@pytest.mark.parametrize(
    ("l1_ratio", "l3_ratio", "field"),
    [
        (0.0, 0.4, "l1_ratio"),
        (1.2, 0.4, "l1_ratio"),
        (0.2, -0.1, "l3_ratio"),
        (0.5, 0.5, "l1_ratio + l3_ratio"),
        (0.6, 0.5, "l1_ratio + l3_ratio"),
        (math.nan, 0.4, "l1_ratio"),
    ],
)
def test_ratios_must_leave_a_positive_femur(l1_ratio, l3_ratio, field):
    with pytest.raises(DesignError) as info:
        HexapodDesign.from_ratios(l1_ratio, l3_ratio)
    assert info.value.field == field


def test_total_must_be_positive():
    with pytest.raises(DesignError, match="total"):
        HexapodDesign.from_ratios(0.1, 0.4, total=-1.0)


@pytest.mark.parametrize("joint", ["theta1", "theta2", "theta3"])
def test_limits_need_lower_below_upper(joint):
    bounds = {"theta1": (-0.5, 0.5), "theta2": (-0.5, 0.5), "theta3": (-2.0, -0.1)}
    bounds[joint] = (0.3, 0.3)
    with pytest.raises(DesignError) as info:
        JointLimits(**bounds, name="stance_limits")
    assert info.value.field == f"stance_limits.{joint}"
    assert "lower bound must be < upper bound" in str(info.value)


def test_nominal_angles_must_lie_within_stance_limits():
    with pytest.raises(DesignError) as info:
        HexapodDesign(nominal_angles=(0.0, 0.9, -1.5))  # hip 0.9 > π/6
    assert info.value.field == "nominal_angles.theta2"
    assert "stance_limits.theta2" in str(info.value)


def test_nominal_stance_with_feet_above_the_body_is_rejected():
    # hip up and knee almost straight: the feet end higher than the body's underside
    with pytest.raises(DesignError) as info:
        HexapodDesign(nominal_angles=(0.0, 0.5, -0.3))
    assert info.value.field == "nominal_angles"
    assert "below the body" in str(info.value)


def test_feet_must_clear_a_tall_body():
    with pytest.raises(DesignError, match="nominal_angles"):
        HexapodDesign(body_height=1.0)  # underside at -0.5 m, feet at -0.4 m


def test_mounts_are_validated():
    mounts = list(default_mounts(1.0, 0.6))
    with pytest.raises(DesignError, match="exactly 6"):
        HexapodDesign(mounts=tuple(mounts[:5]))
    with pytest.raises(DesignError, match="unique"):
        HexapodDesign(mounts=(*mounts[:5], mounts[0]))
    uneven = (*mounts[:5], LegMount("rr", -0.5, -0.3, 0.05, -2.3))
    with pytest.raises(DesignError) as info:
        HexapodDesign(mounts=uneven)
    assert info.value.field == "mounts[*].z"
    with pytest.raises(DesignError, match="yaw"):
        LegMount("lf", 0, 0, 0, 4.0)


@pytest.mark.parametrize("name", ["${__import__('os').system('true')}", "Leg 1", "", "1abc"])
def test_leg_names_are_identifiers_so_xacro_never_evaluates_them(name):
    with pytest.raises(DesignError, match=r"mount\.name"):
        LegMount(name, 0.0, 0.0, 0.0, 0.0)


def test_designs_are_frozen_and_replace_revalidates():
    design = HexapodDesign()
    with pytest.raises(AttributeError):
        design.l1 = 0.3  # type: ignore[misc]
    with pytest.raises(DesignError):
        design.replace(l2=-0.1)
    wider = design.replace(body_width=0.8)
    assert wider.mounts == default_mounts(1.0, 0.8)  # default legs follow the body
    custom = design.replace(mounts=default_mounts(2.0, 1.0))
    assert custom.replace(body_width=0.8).mounts == default_mounts(2.0, 1.0)


def test_as_dict_round_trips_every_field():
    design = HexapodDesign.from_ratios(0.1, 0.45)
    data = design.as_dict()
    assert data["l1"] == pytest.approx(0.1)
    assert len(data["mounts"]) == 6
    assert data["stance_limits"]["theta2"] == list(STANCE_LIMITS.theta2)
    rebuilt = HexapodDesign(
        **{
            **data,
            "mounts": tuple(LegMount(**m) for m in data["mounts"]),
            "nominal_angles": tuple(data["nominal_angles"]),
            **{
                key: JointLimits(
                    tuple(v["theta1"]),
                    tuple(v["theta2"]),
                    tuple(v["theta3"]),
                    v["coupled_knee"],
                    name=key,
                )
                for key, v in data.items()
                if isinstance(v, dict) and "theta1" in v
            },
        }
    )
    assert rebuilt == design.replace(
        **{
            k: getattr(rebuilt, k)
            for k in (
                "workspace_limits",
                "improved_limits",
                "manipulability_limits",
                "stance_limits",
            )
        }
    )


def test_joint_limit_sets_match_the_paper():
    design = HexapodDesign()
    np.testing.assert_allclose(
        design.workspace_limits.lower, [-np.pi / 4, -np.pi / 3, -3 * np.pi / 4]
    )
    np.testing.assert_allclose(design.workspace_limits.upper, [np.pi / 4, np.pi / 3, 0])
    np.testing.assert_allclose(design.stance_limits.lower, [-np.pi / 4, -np.pi / 6, -3 * np.pi / 4])
    np.testing.assert_allclose(design.stance_limits.upper, [np.pi / 4, np.pi / 6, -np.pi / 12])
    np.testing.assert_allclose(
        np.degrees(design.manipulability_limits.lower[1:]), [-60, -135], atol=1e-12
    )
    np.testing.assert_allclose(
        np.degrees(design.manipulability_limits.upper[1:]), [60, -15], atol=1e-12
    )
    improved = design.improved_limits
    # Table 4: θ3 ∈ [-θ2 - π/2, 0]
    assert improved.contains([0.0, 0.5, -0.5 - np.pi / 2 + 1e-9])
    assert not improved.contains([0.0, 0.5, -0.5 - np.pi / 2 - 1e-9])
    assert improved.contains([0.0, np.pi / 3, -5 * np.pi / 6 + 1e-9])


def test_every_field_is_declared_once_and_each_reader_uses_the_declaration(capsys):
    """Docstring, design-file comments and CLI help all come from DESIGN_FIELDS."""
    import inspect
    from dataclasses import fields

    from hexaleg.cli import main
    from hexaleg.design import DESIGN_FIELDS
    from hexaleg.design_text import design_toml

    assert [spec.name for spec in DESIGN_FIELDS] == [f.name for f in fields(HexapodDesign)]
    doc = " ".join(inspect.getdoc(HexapodDesign).split())
    toml = design_toml(HexapodDesign())
    with pytest.raises(SystemExit):
        main(["urdf", "--help"])
    cli = " ".join(capsys.readouterr().out.split())
    for spec in DESIGN_FIELDS:
        described = " ".join(spec.described.split())
        assert f"{spec.name}: {described[0].upper()}{described[1:]}." in doc
        if spec.unit:
            assert f"[{spec.unit}]" in described
        if spec.kind in ("number", "triple", "choice"):
            assert f"{spec.key} = " in toml and f"# {spec.described}" in toml
        elif spec.kind == "limits":
            assert f"[{spec.key}]  # {spec.described}" in toml
        if spec.flag is not None:
            assert f"{spec.flag} " in cli and described in cli
