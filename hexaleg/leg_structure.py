"""The legs' own structure: each segment a round tube of a structural material.

A design file's ``[structure]`` table (:class:`Structure`) names the material (a catalog
entry of :mod:`hexaleg.materials`, or a ``[structure.material]`` table of its own numbers)
and each segment's tube, ``[structure.coxa]``, ``[structure.femur]``, ``[structure.tibia]``:
its outer diameter D [m] and wall t [m] (:class:`Tube`; a solid rod when t = D/2). Every leg
has the same tubes. A segment of length l then weighs ρ·π/4·(D² − (D − 2t)²)·l with its
centre mid-segment, in place of the design's ``link_linear_density``; the foot and the
actuators stay as they are. ``safety_factor`` divides the material's strength,
``deflection_limit`` bounds the foot's deflection (1 % of the leg length when unset), and
``size = true`` asks every command to choose the tubes (:mod:`hexaleg.structure`).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any, cast

from hexaleg.exceptions import ParameterError
from hexaleg.field_spec import FieldSpec, attributes_section, declare, field_specs
from hexaleg.materials import Material, shipped_materials
from hexaleg.table_records import (
    REQUIRED,
    check_record,
    record_from_table,
    require_table,
    unknown_key,
)

TABLE = "structure"
"""The design file's table of the legs' structure."""

LEG_SEGMENTS: tuple[str, str, str] = ("coxa", "femur", "tibia")
"""The segments, from the body out (lengths l1, l2, l3)."""

DEFAULT_DEFLECTION_SHARE = 0.01
"""The foot's deflection limit without ``deflection_limit``: this share of the leg length [-]."""


@dataclass(frozen=True)
class Tube:
    """A round tube: outer diameter and wall; a solid rod when the wall is half the diameter."""

    # fmt: off
    outer_diameter: float = declare(REQUIRED, "outer diameter D", "m", (1e-4, 10.0))
    wall: float = declare(
        REQUIRED, "wall thickness t, at most D/2 (a solid rod)", "m", (1e-6, 5.0)
    )
    # fmt: on

    def __post_init__(self) -> None:
        check_record(self, TUBE_FIELDS)
        if self.wall > self.outer_diameter / 2:
            raise ParameterError(
                "wall",
                self.wall,
                f"must lie in (0, {self.outer_diameter / 2:g}] [m]: at most half the outer "
                f"diameter D = {self.outer_diameter:g} m (a solid rod)",
            )

    @property
    def inner_diameter(self) -> float:
        """D − 2t [m] (0 for a solid rod)."""
        return max(self.outer_diameter - 2 * self.wall, 0.0)

    @property
    def area(self) -> float:
        """Cross-section A = π/4·(D² − d²) [m²]."""
        return math.pi / 4 * (self.outer_diameter**2 - self.inner_diameter**2)

    @property
    def second_moment(self) -> float:
        """Second moment of area about a diameter, I = π/64·(D⁴ − d⁴) [m⁴]."""
        return math.pi / 64 * (self.outer_diameter**4 - self.inner_diameter**4)

    def linear_density(self, material: Material) -> float:
        """Mass per length ρ·A [kg/m]."""
        return material.density * self.area

    def as_dict(self) -> dict[str, float]:
        """The tube's keys [m], as a design file's ``[structure.<segment>]`` table."""
        return {"outer_diameter": self.outer_diameter, "wall": self.wall}


TUBE_FIELDS: tuple[FieldSpec, ...] = field_specs(Tube)
"""A tube's keys, declared once."""

Tube.__doc__ = cast(str, Tube.__doc__).rstrip() + "\n\n" + attributes_section(TUBE_FIELDS)


@dataclass(frozen=True)
class Structure:
    """The legs' structure: a material, each segment's tube, the safety factor, the limits."""

    # fmt: off
    material: Material = declare(
        REQUIRED, "a catalog material's name (hexaleg materials), or a table of its density, "
        "youngs_modulus and yield_strength", kind="record", record=Material,
    )
    coxa: Tube | None = declare(
        None, "the coxa's tube: outer_diameter, wall", "m", kind="record", record=Tube
    )
    femur: Tube | None = declare(
        None, "the femur's tube: outer_diameter, wall", "m", kind="record", record=Tube
    )
    tibia: Tube | None = declare(
        None, "the tibia's tube: outer_diameter, wall", "m", kind="record", record=Tube
    )
    safety_factor: float = declare(
        2.0, "safety factor: the stress allowed is the strength over it", "-", (1.0, 100.0)
    )
    deflection_limit: float | None = declare(
        None, "the foot's largest deflection under the worst standing load; unset: 1 % of the "
        "leg length", "m", (1e-6, 10.0),
    )
    size: bool = declare(
        False, "choose each segment's tube, the lightest that holds (tubes given are replaced)",
        kind="choice",
    )
    # fmt: on

    def __post_init__(self) -> None:
        check_record(self, STRUCTURE_FIELDS)
        if not isinstance(self.size, bool):
            raise ParameterError("size", self.size, "must be true or false")
        for segment, tube in zip(LEG_SEGMENTS, self.tubes, strict=True):
            if tube is None and not self.size:
                raise ParameterError(
                    segment,
                    None,
                    "is missing: give its outer_diameter and wall [m], or size = true",
                )

    @classmethod
    def from_table(cls, table: Any) -> Structure:
        """The structure a design file's ``[structure]`` table describes.

        Raises:
            ParameterError: One line naming ``structure.<key>`` and its range, an unknown
                key with the nearest one, an unknown material with the nearest name.

        """
        table = require_table(TABLE, table, ", ".join(s.name for s in STRUCTURE_FIELDS))
        values: dict[str, Any] = {}
        for key, value in table.items():
            if key not in FIELDS:
                raise unknown_key(TABLE, key, STRUCTURE_FIELDS)
            values[key] = _value(key, value)
        if "material" not in values:
            raise ParameterError(
                f"{TABLE}.material", None, f"is missing: {FIELDS['material'].help}"
            )
        try:
            return cls(**values)
        except ParameterError as err:
            raise ParameterError(f"{TABLE}.{err.field}", err.value, err.allowed) from None

    @property
    def tubes(self) -> tuple[Tube | None, Tube | None, Tube | None]:
        """(coxa, femur, tibia) tubes."""
        return (self.coxa, self.femur, self.tibia)

    @property
    def allowed_stress(self) -> float:
        """The material's strength over the safety factor [Pa]."""
        return self.material.yield_strength / self.safety_factor

    def limit(self, leg_length: float) -> float:
        """The foot's deflection limit [m]: ``deflection_limit``, else 1 % of ``leg_length`` [m]."""
        if self.deflection_limit is not None:
            return self.deflection_limit
        return DEFAULT_DEFLECTION_SHARE * leg_length

    def with_tubes(self, tubes: tuple[Tube, Tube, Tube]) -> Structure:
        """The same structure with these (coxa, femur, tibia) tubes."""
        coxa, femur, tibia = tubes
        return dataclasses.replace(self, coxa=coxa, femur=femur, tibia=tibia)

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready: the material's numbers and source, each tube [m], the factors."""
        return self.to_table() | {"material": self.material.as_dict()}

    def to_table(self) -> dict[str, Any]:
        """The design file's ``[structure]`` table (:meth:`from_table` reads it back)."""
        catalog, name = shipped_materials(), self.material.name
        named = name in catalog.names and catalog.material(name) == self.material
        table: dict[str, Any] = {"material": name if named else self.material.to_table()}
        for segment, tube in zip(LEG_SEGMENTS, self.tubes, strict=True):
            if tube is not None:
                table[segment] = tube.as_dict()
        table["safety_factor"] = self.safety_factor
        if self.deflection_limit is not None:
            table["deflection_limit"] = self.deflection_limit
        return table | {"size": self.size}


STRUCTURE_FIELDS: tuple[FieldSpec, ...] = field_specs(Structure)
"""The ``[structure]`` table's keys, declared once."""

FIELDS: dict[str, FieldSpec] = {spec.name: spec for spec in STRUCTURE_FIELDS}

Structure.__doc__ = (
    cast(str, Structure.__doc__).rstrip() + "\n\n" + attributes_section(STRUCTURE_FIELDS)
)


def _value(key: str, value: Any) -> Any:
    """One key of the ``[structure]`` table as :class:`Structure` takes it."""
    where = f"{TABLE}.{key}"
    if key == "material":
        if isinstance(value, str):
            return shipped_materials().material(value, where)
        return Material.from_table(value, where)
    if key in LEG_SEGMENTS:
        return record_from_table(Tube, TUBE_FIELDS, value, where)
    if key == "size" and not isinstance(value, bool):
        raise ParameterError(where, value, "must be true or false")
    return value


def segment_masses(
    structure: Structure | None, lengths: tuple[float, float, float], linear_density: float
) -> tuple[float, float, float]:
    """Each segment's mass [kg]: its tube's ρ·A·l, else ``linear_density`` [kg/m] times l."""
    masses = [linear_density * length for length in lengths]
    for i, tube in enumerate((None, None, None) if structure is None else structure.tubes):
        if tube is not None:
            masses[i] = tube.linear_density(cast(Structure, structure).material) * lengths[i]
    return (masses[0], masses[1], masses[2])
