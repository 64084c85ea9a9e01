"""``flexibility --urdf FILE --mode free [--collisions]``: an imported robot's free extremes.

Oracles, all on the raw file in Pinocchio (no hexaleg closed form): at each reported
free-coupled extreme, the body at the reported pose and every joint at the file's values
the JSON reports, each stance foot must be on its nominal foothold, every joint within
the file's limits and the body above the ground; where the final local solve converged
(elsewhere the answer is flagged), each binding constraint must be at its bound: a joint
at one of its file limits, a foot out of reach where the leg's foot Jacobian is singular
(knee straight or folded), the body's lowest point on the ground, two parts touching
where coal's distance between them, on the file's own collision geometry, is zero. No
checked pair of parts may overlap at any extreme (that the free range is never short of
the axis-locked one is ``test_free_coupled``'s, for every kind of robot); the template's
URDF imported back gives the template's own free extremes. The searches run with small
budgets (fewer climbs and collision starts): the oracles check what an answer is, not that
it is the best.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import json
import re
import shutil
import warnings
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from conftest import run_cli, small_free_search
from raw_chain import RawChain, body_pose
from robot_files import draw_hexapod
from robots import equal_limits_design

from hexaleg import HexapodDesign
from hexaleg.cli import main
from hexaleg.exceptions import RobotImportWarning
from hexaleg.limits import LEG_JOINTS, STANCE_LIMITS
from hexaleg.robot.imported import import_robot, robot_from_text
from hexaleg.robot.imported_model import ImportedHexapodModel
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.urdf import render_hexapod
from hexaleg.stance.configurations import stance_configurations
from hexaleg.stance.flexibility import flexibility
from hexaleg.stance.geometry import (
    StanceGeometry,
    stance_forward_kinematics,
    stance_inverse_kinematics,
)
from hexaleg.stance.margin_jacobian import pose_margins_and_jacobian
from hexaleg.stance.margin_kernel import column_count, kernel_geometry, margins_of
from hexaleg.stance.symmetry import MIRRORS, mirror_flips

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = ROBOTS / "kraby" / "hexapod.urdf"
OCHS = ROBOTS / "phantomx_kevinochs" / "urdf" / "phantomX_model.xacro"
OCHS_FOOT = ["--foot-offset", "0", "0.133", "0"]
AT_BOUND = 1e-6
"""A binding joint or the ground this close to its bound [rad or m]."""
SINGULAR = 1e-3
"""A leg out of reach: its foot Jacobian's smallest singular value below this of its largest."""
TOUCHING = 3e-5
"""Two parts that touch are this close [m] (hexaleg stops 1e-5 m short of contact)."""


def _json(argv):
    out = io.StringIO()
    with warnings.catch_warnings(), contextlib.redirect_stdout(out):
        warnings.simplefilter("ignore", RobotImportWarning)
        assert main(argv) == 0
    return json.loads(out.getvalue())


def _drawn(folder, seed):
    text, _ = draw_hexapod(seed, same_legs=True)
    path = folder / f"drawn{seed}.urdf"
    path.write_text(text)
    return path


ROBOT_CASES = {
    "kraby": (KRABY, []),
    "phantomx": (OCHS, OCHS_FOOT),
    "drawn 3 (hip height, lateral offset, bends)": ("drawn:3", []),
}


@pytest.fixture(scope="module")
def small_search():
    """This module's free-coupled searches with small budgets."""
    with pytest.MonkeyPatch.context() as patch:
        small_free_search(patch)
        yield


@pytest.fixture(scope="module", params=list(ROBOT_CASES))
def robot(request, small_search, tmp_path_factory):
    """A robot's options, its axis-locked and free JSON, and its raw chain."""
    path, options = ROBOT_CASES[request.param]
    if str(path).startswith("drawn:"):
        path = _drawn(tmp_path_factory.mktemp("drawn"), int(str(path).split(":")[1]))
    argv = ["--urdf", str(path), *options]
    shown = _json(["design", "show", *argv, "--json"])
    offset = (0.0, 0.133, 0.0) if options == OCHS_FOOT else None
    return {
        "axis": _json(["flexibility", *argv, "--json"]),
        "free": _json(["flexibility", *argv, "--mode", "free", "--json"]),
        "chain": RawChain(str(path), offset, shown),
        "argv": argv,
    }


def _posed(chain, extreme, height):
    body = body_pose(np.asarray(extreme["pose"]), height)
    return body, chain.configuration(body, extreme["urdf_joint_angles"])


def _file_values(chain, q, leg):
    return np.array([q[j.idx_q] for j in chain.joints(leg)])


def _file_limits(chain, leg):
    limits = chain.legs[leg]["file_limits"]
    return np.asarray(limits["lower"]), np.asarray(limits["upper"])


def _flagged(result, extreme):
    """Whether the result warns that ``extreme`` is not shown to be the maximum."""
    name = f"{extreme['axis']}{'+' if extreme['sign'] > 0 else '-'}:"
    return not result["converged"] and any(w.startswith(name) for w in result["warnings"])


def test_each_free_extreme_is_a_closed_chain_of_the_raw_file_at_its_binding_bounds(robot):
    chain, result = robot["chain"], robot["free"]
    assert result["mode"] == "free"
    height, footholds = chain.standing(result["stance"])
    for extreme in result["extremes"]:
        body, q = _posed(chain, extreme, height)
        name = extreme["description"]
        for leg in result["stance"]:
            foot, _ = chain.foot(leg, q)
            np.testing.assert_allclose(foot, footholds[leg], atol=1e-6, err_msg=name)
            lower, upper = _file_limits(chain, leg)
            values = _file_values(chain, q, leg)
            assert np.all(values >= lower - 1e-9) and np.all(values <= upper + 1e-9), (name, leg)
        assert chain.clearance(body) >= -1e-9, name
        if not extreme["evidence"]["polished"]:  # a climb's end, flagged: not at a bound
            assert _flagged(result, extreme)
            continue
        for cause in extreme["binding"]:
            if cause["kind"] == "joint":
                value = _file_values(chain, q, cause["leg"])[LEG_JOINTS.index(cause["joint"])]
                bounds = np.array(_file_limits(chain, cause["leg"]))[
                    :, LEG_JOINTS.index(cause["joint"])
                ]
                assert np.abs(bounds - value).min() < AT_BOUND, (name, cause["description"])
            elif cause["kind"] == "reach":
                singular = np.linalg.svd(chain.foot(cause["leg"], q)[1], compute_uv=False)
                assert singular[-1] < SINGULAR * singular[0], (name, cause["description"])
            else:
                assert cause["kind"] == "ground" and cause["leg"] is None, cause
                assert abs(chain.clearance(body)) < AT_BOUND, name


def test_loads_take_the_free_extremes_of_an_imported_robot(robot):
    loads = _json(["loads", *robot["argv"], "--mode", "free", "--json"])
    assert loads["extremes_mode"] == "free"
    values = [e["value"] for e in loads["extremes"]]
    np.testing.assert_allclose(values, [e["value"] for e in robot["free"]["extremes"]], atol=1e-9)


@pytest.mark.parametrize("layout", ["rectangle", "hexagon"])
def test_the_template_urdf_imported_back_has_the_designs_free_extremes(layout):
    design = equal_limits_design(layout)
    own = flexibility(design, "free", "all", HexapodModel(design))
    model = ImportedHexapodModel(robot_from_text(render_hexapod(design)), design)
    back = flexibility(model.design, "free", "all", model)
    assert back.fb == pytest.approx(own.fb, abs=1e-6)
    for mine, theirs in zip(back.extremes, own.extremes, strict=True):
        assert mine.value == pytest.approx(theirs.value, abs=1e-6), theirs.name
        np.testing.assert_allclose(mine.pose, theirs.pose, atol=1e-6)


def test_the_margins_jacobian_of_a_general_leg_equals_central_differences(tmp_path):
    """The climbs' closed-form Jacobian, with a hip height and a lateral offset.

    Against central differences (step 1e-6) of the compiled smooth margins themselves.
    """
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        model = ImportedHexapodModel(import_robot(_drawn(tmp_path, 3)))
    geometry = StanceGeometry.from_model(model)
    legs = geometry.leg_geometries
    assert all(abs(g.hip_height) > 1e-3 and abs(g.foot_lateral) > 1e-3 for g in legs)
    kernel = kernel_geometry([geometry], smooth=True)
    columns = column_count(kernel)

    def margins(d):
        d = np.ascontiguousarray(np.reshape(d, (-1, 6)), dtype=float)
        return margins_of(kernel, d, np.zeros(len(d), dtype=np.int64))

    rng = np.random.default_rng(3)
    for d in rng.uniform(-1, 1, size=(8, 6)) * np.array([0.03, 0.03, 0.02, 0.1, 0.1, 0.2]):
        values, jacobian = np.empty(columns), np.empty((columns, 6))
        pose_margins_and_jacobian(kernel, 0, d, values, jacobian)
        np.testing.assert_allclose(values, margins(d)[0], atol=1e-12)
        steps = 1e-6 * np.eye(6)
        central = ((margins(d + steps) - margins(d - steps)) / 2e-6).T
        np.testing.assert_allclose(jacobian, central, rtol=1e-6, atol=1e-6)


def _kraby_with_a_body_mesh(folder):
    """Kraby with its body's mesh drawn (a plate, in millimetres, as the file reads it).

    The file's leg parts are kept to its servos' boxes (the brackets, feet and end caps
    dropped) so that the search with collisions stays short; the file is otherwise Kraby's.
    """
    import trimesh

    text = re.sub(
        r'(<link name="(?:foot|endcap|joint)_\d+">.*?)<collision>.*?</collision>',
        r"\1",
        KRABY.read_text(),
        flags=re.S,
    )
    (folder / "meshes").mkdir()
    plate = trimesh.creation.box(extents=(100.0, 70.0, 20.0))
    plate.apply_translation((0.0, 0.0, -203.0))  # the file places it 0.203 m up
    plate.export(folder / "meshes" / "box.stl")
    path = folder / "hexapod.urdf"
    path.write_text(text)
    return path


class _Parts:
    """The raw file's collision geometry in Pinocchio (coal), its pairs as hexaleg's rule says.

    Every pair of parts except those on one rigid body or on two bodies joined by a joint.
    """

    def __init__(self, chain, path):
        model = chain.model
        self.chain = chain
        self.geometry = pin.buildGeomFromUrdf(
            model, str(path), pin.GeometryType.COLLISION, package_dirs=[str(path.parent)]
        )
        objects = self.geometry.geometryObjects
        self.names = [model.frames[o.parentFrame].name for o in objects]
        joint = [o.parentJoint for o in objects]
        for a in range(len(objects)):
            for b in range(a + 1, len(objects)):
                i, j = joint[a], joint[b]
                if i != j and model.parents[i] != j and model.parents[j] != i:
                    self.geometry.addCollisionPair(pin.CollisionPair(a, b))
        self.data = pin.GeometryData(self.geometry)

    def distances(self, q):
        """Each checked pair's distance at q [m], by link names; and whether any overlap."""
        chain = self.chain
        pin.computeDistances(chain.model, chain.data, self.geometry, self.data, q)
        found = {}
        for pair, result in zip(
            self.geometry.collisionPairs, self.data.distanceResults, strict=True
        ):
            key = frozenset((self.names[pair.first], self.names[pair.second]))
            found[key] = min(found.get(key, np.inf), result.min_distance)
        overlap = pin.computeCollisions(chain.model, chain.data, self.geometry, self.data, q, False)
        return found, overlap


@pytest.fixture(scope="module")
def collided(small_search, tmp_path_factory):
    """Kraby's free extremes with collisions, its raw chain and its parts."""
    path = _kraby_with_a_body_mesh(tmp_path_factory.mktemp("kraby"))
    argv = ["--urdf", str(path)]
    chain = RawChain(str(path), None, _json(["design", "show", *argv, "--json"]))
    result = _json(["flexibility", *argv, "--mode", "free", "--collisions", "--json"])
    return result, chain, _Parts(chain, path)


@pytest.mark.slow
def test_free_extremes_with_collisions_touch_where_they_say_and_overlap_nowhere(collided):
    result, chain, parts = collided
    assert result["collisions"] and "box" in parts.names  # the body's mesh, found by the file
    height, footholds = chain.standing(result["stance"])
    touching = 0
    for extreme in result["extremes"]:
        _, q = _posed(chain, extreme, height)
        for leg in result["stance"]:
            np.testing.assert_allclose(chain.foot(leg, q)[0], footholds[leg], atol=1e-6)
        distances, overlap = parts.distances(q)
        assert not overlap and min(distances.values()) > 0, extreme["description"]
        if not extreme["evidence"]["polished"]:
            assert _flagged(result, extreme)
            continue
        for cause in extreme["binding"]:
            if cause["kind"] == "collision":
                touching += 1
                distance = distances[frozenset(cause["links"])]
                assert distance < TOUCHING, (extreme["description"], distance)
    assert touching > 0  # the test saw parts touch


def test_a_collision_mesh_not_found_is_left_out_with_a_warning(tmp_path):
    alone = tmp_path / "hexapod.urdf"  # the file without the meshes folder beside it
    shutil.copy(KRABY, alone)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        model = ImportedHexapodModel(import_robot(alone))
    with pytest.warns(RobotImportWarning, match="meshes/box.stl"):
        geometry = model.collision_model()
    names = {model.model.frames[o.parentFrame].name for o in geometry.geometryObjects}
    assert "box" not in names and {"servomotor_0", "endcap_5"} <= names


def test_collisions_without_any_part_to_check_are_refused_in_one_line(capsys):
    """PhantomX's meshes are not shipped: no part is left to check."""
    argv = ["flexibility", "--urdf", str(OCHS), *OCHS_FOOT, "--collisions", "--mode", "free"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        assert run_cli(argv) == 2
    captured = capsys.readouterr()
    error = [line for line in captured.err.splitlines() if "error" in line]
    assert captured.out == "" and len(error) == 1 and "no two of the robot's parts" in error[0]


@pytest.mark.parametrize("seed", [3, 5])
def test_stance_kinematics_of_a_general_leg_put_the_models_feet_on_their_footholds(tmp_path, seed):
    """IK by each leg's own geometry, checked by Pinocchio's FK of the model; FK inverts it."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        model = ImportedHexapodModel(import_robot(_drawn(tmp_path, seed)))
    geometry = StanceGeometry.from_model(model)
    rng = np.random.default_rng(seed)
    for d in rng.uniform(-1, 1, size=(5, 6)) * np.array([0.01, 0.01, 0.01, 0.05, 0.05, 0.05]):
        body = pin.SE3(pin.rpy.rpyToMatrix(*d[3:]), d[:3] + geometry.nominal_pose.translation)
        solution = stance_inverse_kinematics(geometry, body)
        assert solution.reachable.all()
        q = model.configuration(body, dict(zip(geometry.legs, solution.theta, strict=True)))
        index = [model.leg_names.index(leg) for leg in geometry.legs]
        np.testing.assert_allclose(model.foot_positions(q)[index], geometry.footholds, atol=1e-9)
        fitted = stance_forward_kinematics(geometry, solution.theta)
        np.testing.assert_allclose(fitted.homogeneous, body.homogeneous, atol=1e-9)
    # the configurations the self-collision check poses: the same feet on their footholds
    d = rng.uniform(-1, 1, size=(5, 6)) * np.array([0.01, 0.01, 0.01, 0.05, 0.05, 0.05])
    for q in stance_configurations(model, geometry, d):
        np.testing.assert_allclose(model.foot_positions(q)[index], geometry.footholds, atol=1e-9)


def _template_back(**changes):
    """The default design's stance read from its own URDF imported back, legs changed."""
    limits = STANCE_LIMITS
    design = HexapodDesign(
        workspace_limits=limits,
        improved_limits=limits,
        manipulability_limits=limits,
        stance_limits=limits,
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RobotImportWarning)
        model = ImportedHexapodModel(robot_from_text(render_hexapod(design)), design)
    geometry = StanceGeometry.from_model(model)
    legs = list(geometry.leg_geometries)
    bounds = np.array(geometry.leg_bounds)
    for leg, (lateral, root) in changes.items():
        n = geometry.legs.index(leg)
        legs[n] = dataclasses.replace(legs[n], foot_lateral=lateral)
        bounds[:, n, 0] = root
    return dataclasses.replace(geometry, leg_geometries=tuple(legs), leg_bounds=bounds)


MIRRORED = {"lf": (0.01, (-0.5, 0.7)), "rf": (-0.01, (-0.7, 0.5))}
"""A left-right pair of general legs: lateral offsets and root limits [m, rad] mirrored."""


@pytest.mark.parametrize(
    ("changes", "expected"),
    [
        (MIRRORED, {"left-right"}),
        ({**MIRRORED, "rf": (0.01, (-0.7, 0.5))}, set()),  # e not mirrored
        ({**MIRRORED, "rf": (-0.01, (-0.5, 0.7))}, set()),  # root limits not mirrored
    ],
    ids=["mirrored pair", "lateral offset", "root limits"],
)
def test_a_general_legs_mirror_is_found_where_every_margin_mirrors(changes, expected):
    """The flips found are those under which the exact margins are a permutation."""
    geometry = _template_back(**changes)
    found = {name for name, (_, flip) in MIRRORS.items() if _has(mirror_flips(geometry), flip)}
    assert found == expected
    kernel = kernel_geometry([geometry], smooth=False)
    d = np.random.default_rng(0).uniform(-1, 1, size=(16, 6)) * 0.05
    design = np.zeros(len(d), dtype=np.int64)
    for name, (_, flip) in MIRRORS.items():
        here = np.sort(margins_of(kernel, d, design), axis=-1)
        there = np.sort(margins_of(kernel, np.ascontiguousarray(d * flip), design), axis=-1)
        assert np.allclose(here, there, atol=1e-12) == (name in expected), name


def _has(flips, flip):
    return any(np.array_equal(f, flip) for f in flips)


def test_the_template_urdf_imported_back_collides_where_the_design_does():
    """A short body's coxae touch: the file's geometry (the template's own) stops it there."""
    limits = STANCE_LIMITS
    design = HexapodDesign(
        body_length=0.1,
        body_width=0.4,
        workspace_limits=limits,
        improved_limits=limits,
        manipulability_limits=limits,
        stance_limits=limits,
    )
    own = flexibility(design, "axis", "all", HexapodModel(design), collisions=True)
    model = ImportedHexapodModel(robot_from_text(render_hexapod(design)), design)
    back = flexibility(model.design, "axis", "all", model, collisions=True)
    assert any(e.limited_by.kind == "collision" for e in own.extremes)
    for mine, theirs in zip(back.extremes, own.extremes, strict=True):
        assert mine.value == pytest.approx(theirs.value, abs=1e-9), theirs.name
        assert mine.binding == theirs.binding, theirs.name
