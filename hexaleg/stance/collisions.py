"""Self-collision: the robot's own parts touching, as one more constraint on the body.

The geometry is the URDF's collision geometry (the template's body box and each leg
link's cylinder; a robot file's own shapes and meshes:
:meth:`~hexaleg.robot.model.HexapodModel.collision_model`), read by Pinocchio into a
geometry model; distances come from coal through ``pinocchio.computeDistances``. Every
pair of parts is checked except those on one rigid body or on two bodies joined by a
joint (the body and a coxa, a coxa and its femur, a femur and its tibia), which touch
by construction. Each part is named by the link that carries it. The clearance (smallest
distance over the pairs) is a margin like the others: ≥ 0 holds.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from hexaleg._typing import ArrayF
from hexaleg.cause import Cause
from hexaleg.exceptions import HexalegError
from hexaleg.numerics.bracketing import IndexArray, first_crossings
from hexaleg.robot.model import HexapodModel
from hexaleg.stance.configurations import posed_configurations
from hexaleg.stance.constraints import AXES, direction_poses, displacement_poses
from hexaleg.stance.extremes import Extreme, pose_extreme
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.stance.symmetry import mirror_sources, search_flips

COLLISION_SCAN_STEPS = 16
"""Resolution of the collision scan along each direction, up to its other extreme."""
COLLISION_SCAN_CHUNKS = 4
"""The scan runs in this many chunks: a direction stops being scanned once it collides."""
COLLISION_TOLERANCE = 1e-8
"""Bracket width of a collision crossing, relative to the searched distance: coal's
distances near contact are good to a few 1e-7 m, so a tighter root means nothing."""
TIE_DISTANCE = 1e-6
"""Pairs this close to the closest [m] touch together (mirror-image legs do; coal tells
their distances apart only to about 2e-7 m near contact)."""
CONTACT_DISTANCE = 1e-5
"""Two parts touch when closer than this [m] (10 µm): coal resolves distances near
contact only to a few 1e-7 m and reports intersecting cylinders at distance 0, so a
pose reported collision-free is so with this margin to spare."""
GJK_TOLERANCE = 1e-9
"""coal's GJK stops within this [m] (its default, 1e-6, leaves a distance depending on the
queries before it by up to 2e-6 m: SLSQP's differences of step 1e-5 then follow noise)."""


class SelfCollision:
    """Distances between the robot's own parts at stance poses.

    Attributes:
        pairs: The checked pairs, as link names.
        mirrored: Whether the parts are known to be drawn mirror-symmetric, as hexaleg's
            template draws them (a robot file's may not be: its searches use no mirror).

    """

    def __init__(self, model: HexapodModel, geometry: StanceGeometry) -> None:
        self.model = model
        self.geometry = geometry
        self.mirrored = model.mirror_symmetric
        self.geometry_model = model.collision_model()
        self.geometry_model.addAllCollisionPairs()
        parent_joints = [o.parentJoint for o in self.geometry_model.geometryObjects]
        parents = list(model.model.parents)

        def joined(pair: pin.CollisionPair) -> bool:
            a, b = parent_joints[pair.first], parent_joints[pair.second]
            return a == b or parents[a] == b or parents[b] == a

        kept = [p for p in self.geometry_model.collisionPairs if not joined(p)]
        self.geometry_model.removeAllCollisionPairs()
        for pair in kept:
            self.geometry_model.addCollisionPair(pair)
        self.geometry_data = pin.GeometryData(self.geometry_model)
        for request in self.geometry_data.collisionRequests:  # "touching" for coal's yes/no
            request.security_margin = CONTACT_DISTANCE
        for distance_request in self.geometry_data.distanceRequests:
            distance_request.gjk_tolerance = GJK_TOLERANCE
        _without_warm_starts(self.geometry_data)
        frames = model.model.frames
        names = [frames[o.parentFrame].name for o in self.geometry_model.geometryObjects]
        self.pairs: tuple[tuple[str, str], ...] = tuple(
            (names[p.first], names[p.second]) for p in self.geometry_model.collisionPairs
        )
        if not self.pairs:
            raise HexalegError(
                "self-collision: no two of the robot's parts can touch (no collision geometry "
                "beyond parts joined by a joint; a robot file's meshes not found are left out)"
            )
        nominal = self.clearance(np.eye(3), np.array([0.0, 0.0, geometry.nominal_height]))
        if nominal[0] <= 0:
            raise HexalegError(f"at the nominal stance, {nominal[1]}: the design collides")

    def configurations(self, rotation: ArrayF, translation: ArrayF) -> ArrayF:
        """Configurations (P, nq) for body poses (P, 3, 3), (P, 3), stance legs by the IK."""
        return posed_configurations(self.model, self.geometry, rotation, translation)

    def distances(self, rotation: ArrayF, translation: ArrayF) -> ArrayF:
        """Distance of every pair [m] at one body pose (feet on their footholds)."""
        self._compute(self.configurations(rotation, translation)[0])
        return np.array([r.min_distance for r in self.geometry_data.distanceResults])

    def pair_clearances(self, rotation: ArrayF, translation: ArrayF) -> ArrayF:
        """Every pair's distance less :data:`CONTACT_DISTANCE` at each body pose (P, pairs) [m]."""
        rows = []
        for q in self.configurations(rotation, translation):
            self._compute(q)
            rows.append([r.min_distance for r in self.geometry_data.distanceResults])
        return np.array(rows) - CONTACT_DISTANCE

    def clearances(self, rotation: ArrayF, translation: ArrayF) -> tuple[ArrayF, list[int]]:
        """The clearance at each body pose (P,) [m], and the closest pair's index.

        The clearance is the smallest distance less :data:`CONTACT_DISTANCE`: ≥ 0 holds.
        """
        distances, closest = [], []
        for q in self.configurations(rotation, translation):
            index = self._compute(q)
            distances.append(self.geometry_data.distanceResults[index].min_distance)
            closest.append(index)
        return np.array(distances) - CONTACT_DISTANCE, closest

    def scan_clearances(self, rotation: ArrayF, translation: ArrayF) -> ArrayF:
        """The clearance at each pose where two parts touch, +inf where none do (P,) [m].

        Coal's yes/no collision check (parts closer than :data:`CONTACT_DISTANCE`) costs
        half of every pair's distance: a scan that mostly meets no contact asks it first.
        """
        clearances = np.full(len(np.asarray(rotation).reshape(-1, 9)), np.inf)
        for k, q in enumerate(self.configurations(rotation, translation)):
            if pin.computeCollisions(
                self.model.model, self.model.data, self.geometry_model, self.geometry_data, q, True
            ):
                index = self._compute(q)
                clearances[k] = self.geometry_data.distanceResults[index].min_distance
        return clearances - CONTACT_DISTANCE

    def clearance(self, rotation: ArrayF, translation: ArrayF) -> tuple[float, Cause]:
        """The clearance [m] at one body pose, and the pair it is between."""
        distances, closest = self.clearances(rotation, translation)
        return float(distances[0]), Cause("collision", links=self.pairs[closest[0]])

    def closest_pairs(self, rotation: ArrayF, translation: ArrayF) -> list[Cause]:
        """Every pair as close as the closest (within coal's resolution), in pair order."""
        distances = self.distances(rotation, translation)
        tied = np.flatnonzero(distances <= distances.min() + TIE_DISTANCE)
        return [Cause("collision", links=self.pairs[i]) for i in tied]

    def _compute(self, q: ArrayF) -> int:
        """Distances of every pair at ``q``; the index of the closest pair."""
        return int(
            pin.computeDistances(
                self.model.model, self.model.data, self.geometry_model, self.geometry_data, q
            )
        )


def collision_limited(
    geometry: StanceGeometry, collision: SelfCollision, extremes: Sequence[Extreme]
) -> tuple[Extreme, ...]:
    """Axis-locked extremes cut short where two parts touch first along each direction.

    Each direction is scanned from nominal to its extreme (:data:`COLLISION_SCAN_STEPS`
    steps); where the clearance turns negative, the crossing is solved on the clearance.
    A robot standing on all its legs that is its own mirror image scans one of each
    mirrored pair of directions and takes the other from the mirror
    (:func:`~hexaleg.stance.symmetry.mirror_sources`), its touching pairs found at the
    mirrored pose.
    """
    every_leg_stands = len(geometry.legs) == len(collision.model.leg_names) and collision.mirrored
    directions = [(e.axis, e.sign) for e in extremes]
    sources = mirror_sources(directions, search_flips(geometry, every_leg_stands))
    scanned = [k for k in range(len(extremes)) if k not in sources]
    limited = dict(
        zip(scanned, _scanned(geometry, collision, [extremes[k] for k in scanned]), strict=True)
    )
    for k, (source, flip) in sources.items():
        if limited[source] is extremes[source]:  # nothing touches: nor in the mirror
            limited[k] = extremes[k]
        else:
            displacement = flip * np.asarray(limited[source].pose)
            limited[k] = _touching(geometry, collision, extremes[k], displacement)
    return tuple(limited[k] for k in range(len(extremes)))


def _scanned(
    geometry: StanceGeometry, collision: SelfCollision, extremes: Sequence[Extreme]
) -> list[Extreme]:
    """Each of ``extremes`` scanned for contact from nominal, cut short where parts touch."""
    axis_of = np.array([AXES.index(e.axis) for e in extremes])
    sign_of = np.array([e.sign for e in extremes], dtype=float)

    def poses(direction: IndexArray, t: ArrayF) -> tuple[ArrayF, ArrayF]:
        return direction_poses(geometry, axis_of[direction], sign_of[direction] * t)

    def clearance(direction: IndexArray, t: ArrayF) -> ArrayF:
        return collision.clearances(*poses(direction, t))[0][:, None]

    def touching(direction: IndexArray, t: ArrayF) -> ArrayF:
        return collision.scan_clearances(*poses(direction, t))[:, None]

    crossings = first_crossings(  # the nominal stance's clearance is checked on construction
        clearance,
        np.array([abs(e.value) for e in extremes]),
        steps=COLLISION_SCAN_STEPS,
        chunks=COLLISION_SCAN_CHUNKS,
        tolerance=COLLISION_TOLERANCE,
        check_start=False,
        scan=touching,
    )
    limited = []
    for i, extreme in enumerate(extremes):
        if crossings.which[i] < 0:
            limited.append(extreme)
            continue
        displacement = np.zeros(len(AXES))
        displacement[axis_of[i]] = sign_of[i] * crossings.t[i]
        limited.append(_touching(geometry, collision, extreme, displacement))
    return limited


def _touching(
    geometry: StanceGeometry, collision: SelfCollision, extreme: Extreme, displacement: ArrayF
) -> Extreme:
    """``extreme``'s direction stopped at ``displacement`` by the parts that touch there."""
    rotation, translation = displacement_poses(geometry, displacement)
    binding = collision.closest_pairs(rotation, translation)
    return pose_extreme(geometry, extreme.axis, extreme.sign, displacement, binding)


def _without_warm_starts(data: pin.GeometryData) -> None:
    """Every query of ``data`` starts coal's GJK from its default guess, not the last answer.

    Pinocchio's requests warm-start each pair's GJK from its previous query, so that a
    distance near contact follows the queries before it (by up to 1e-7 m): SLSQP's steps
    then follow that history, and round-off anywhere (the BLAS that SLSQP's own linear
    algebra runs on, its thread count) sends the search to other poses and other optima.
    Without the warm start a distance is a function of the pose alone.
    """
    with warnings.catch_warnings():  # deprecated in coal 3 (for gjk_initial_guess), still read
        warnings.simplefilter("ignore", DeprecationWarning)
        for request in [*data.collisionRequests, *data.distanceRequests]:
            request.enable_cached_gjk_guess = False
