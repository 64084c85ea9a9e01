"""Flexibility results: FB is eq 29, every documented field, modes checked once."""

from __future__ import annotations

import math

import pytest

from hexaleg.stance import AXES, DIRECTIONS, flexibility, flexibility_index


def test_fb_is_eq29(hexapod_model, default_design):
    result = flexibility(default_design, "axis", "all", hexapod_model)
    ranges = result.ranges
    expected = (
        (ranges["x"] + ranges["y"] + ranges["z"]) / (2 * default_design.leg_length)
        + math.degrees(ranges["roll"] + ranges["pitch"] + ranges["yaw"]) / 180
    ) / 6
    assert result.fb == pytest.approx(expected, rel=1e-14)
    assert flexibility_index({a: 0.0 for a in AXES}, 1.0) == 0.0
    # a body that can move ±L along every axis and ±90° about every axis has FB = 1
    full = {**{a: 2.0 for a in AXES[:3]}, **{a: math.pi for a in AXES[3:]}}
    assert flexibility_index(full, 1.0) == pytest.approx(1.0)


def test_to_dict_has_every_documented_field(hexapod_model, default_design):
    data = flexibility(default_design, "axis", "tripod", hexapod_model).to_dict()
    assert set(data["ranges"]) == set(AXES)
    assert len(data["extremes"]) == len(DIRECTIONS) == 12
    assert {"axis", "sign", "value", "limited_by"} <= set(data["extremes"][0])
    design = data["design"]
    assert {"l1", "l2", "l3", "body_length", "mounts", "nominal_angles", "stance_limits"} <= set(
        design
    )
    assert len(design["mounts"]) == 6 and {"x", "y", "z", "yaw"} <= set(design["mounts"][0])


def test_unknown_mode_is_an_error(default_design):
    from hexaleg.exceptions import HexalegError

    with pytest.raises(HexalegError, match="mode"):
        flexibility(default_design, "sideways")


def test_a_plot_label_names_the_first_cause_and_counts_the_others():
    from hexaleg.cause import Cause
    from hexaleg.stance.extremes import Extreme

    knee = Cause("joint", "lf", "knee", "upper")
    alone = Extreme("z", -1, -0.2, knee)
    assert alone.label == alone.description == "lf knee joint at its upper limit"
    mirrored = Extreme("z", -1, -0.2, knee, (knee, Cause("joint", "rf", "knee", "upper")))
    assert mirrored.label == mirrored.description == "lf, rf knee joint at its upper limit"
    mixed = Extreme(
        "z", -1, -0.2, knee, (knee, Cause("joint", "lr", "hip", "lower"), Cause("ground"))
    )
    assert mixed.description.startswith("lf knee joint at its upper limit (also lr hip")
    assert mixed.label == "lf knee joint at its upper limit (+2 more)"
