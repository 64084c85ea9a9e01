"""Robot files under hostile input: reading, parsing and building end in one line or a true answer.

Each row of :data:`CASES` is a folder as a user left it (Kraby's URDF edited the way the fuzz
run edited it, FIFOs, devices, sparse files), a command, and the one line it must end with
(exit status 2, nothing written, nothing of the user's changed), run by
:func:`test_fuzz_cases._check` within a deadline. Where the file is valid, the answer is
held against an oracle: the same robot written plainly (without entities, with its masses),
or the XML the answer must parse to.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from conftest import run_cli
from test_fuzz_cases import FIFO, Case, Sparse, _check

from hexaleg.robot import source
from hexaleg.robot.description import MAX_TREE_DEPTH

ROBOTS = Path(__file__).parent / "data" / "robots"
KRABY = (ROBOTS / "kraby" / "hexapod.urdf").read_text()
FIRST_LIMIT = '<limit effort="1.18" velocity="6.308" lower="-1.57" upper="1.57" />'
"""The first leg joint's (``servomotor_0``) limit as Kraby writes it."""
FIRST_ORIGIN = 'xyz="0.06521292289492935 -0.06521292289492935 0.2041193"'
"""The origin of Kraby's first joint, ``fixed_box_servomotor_0``."""


def kraby(old: str, new: str) -> str:
    """Kraby's URDF with the first ``old`` replaced by ``new``."""
    assert old in KRABY
    return KRABY.replace(old, new, 1)


def renamed(link: str, name: str) -> str:
    """Kraby with link ``link`` renamed to ``name`` (written escaped, as XML requires)."""
    escaped = name.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;")
    return KRABY.replace(f'link="{link}"', f'link="{escaped}"').replace(
        f'<link name="{link}"', f'<link name="{escaped}"'
    )


def deep(depth: int) -> str:
    """Kraby with a chain of ``depth`` links on fixed joints hanging from its body."""
    parts, parent = [], "box"
    for i in range(depth):
        parts.append(
            f'<link name="c{i}"/><joint name="cj{i}" type="fixed"><parent link="{parent}"/>'
            f'<child link="c{i}"/></joint>'
        )
        parent = f"c{i}"
    return KRABY.replace("</robot>", "".join(parts) + "</robot>")


MASSLESS = re.sub(r"<inertial>.*?</inertial>", "", KRABY, flags=re.S)
"""Kraby as a kinematics-only file: no link has an ``<inertial>``."""
XACRO = '<robot xmlns:xacro="http://www.ros.org/wiki/xacro" name="{name}">{body}</robot>'
DOUBLING = "".join(f'<xacro:property name="s{i + 1}" value="${{s{i} + s{i}}}"/>' for i in range(64))
NESTED = '<xacro:macro name="m0"><link name="x"/></xacro:macro>' + "".join(
    f'<xacro:macro name="m{i + 1}"><xacro:m{i}/><xacro:m{i}/></xacro:macro>' for i in range(40)
)
ROBOT_TABLE = '[robot]\nurdf = "{}"\n'
INCLUDE = '<xacro:include filename="in.xacro"/>'
NO_MASSES = "m.urdf gives no masses (no link has an <inertial> with a mass)"
HUGE = 3 * 2**30
"""A mesh of 3 GiB, sparse: it costs no disk, and reading it whole would cost the memory."""

CASES = [
    # 1: what Pinocchio refuses, named up front
    *(Case(f"{argv[0]}: <limit> {attribute} {shown}", {"n.urdf": kraby(FIRST_LIMIT, limit)},
           [*argv, "--urdf", "n.urdf"], f"joint 'servomotor_0' {message}")
      for argv in (["loads"], ["design", "show"], ["gait"])
      for attribute, shown, limit, message in (
          ("effort", "-5", FIRST_LIMIT.replace('"1.18"', '"-5"'),
           "<limit> effort = -5 is negative: a rating is at least 0 [N·m or N]"),
          ("velocity", "-1", FIRST_LIMIT.replace('"6.308"', '"-1"'),
           "<limit> velocity = -1 is negative: a rating is at least 0 [rad/s or m/s]"),
          ("effort", "missing", FIRST_LIMIT.replace(' effort="1.18"', ""),
           "has a <limit> without effort: URDF requires effort and velocity in every <limit>"),
          ("velocity", "missing", FIRST_LIMIT.replace(' velocity="6.308"', ""),
           "has a <limit> without velocity: URDF requires effort and velocity in every <limit>"),
      )),
    # 2: no masses: what needs them refuses
    *(Case(f"{argv[0]} of a file without masses", {"m.urdf": MASSLESS},
           [*argv, "--urdf", "m.urdf"], NO_MASSES)
      for argv in (["loads"], ["loads", "--json"], ["gait"], ["decide", "--evaluations", "60"],
                   ["report", "-o", "r"], ["study", "-o", "s"])),
    # 6: a tree deeper than Pinocchio's parser can recurse
    *(Case(f"{argv[0]} of a {MAX_TREE_DEPTH + 4000}-deep chain", {"deep.urdf": deep(5000)},
           [*argv, "--urdf", "deep.urdf"],
           f"deep.urdf: link c{MAX_TREE_DEPTH} lies {MAX_TREE_DEPTH + 1} joints below the root "
           f"link box; hexaleg reads trees at most {MAX_TREE_DEPTH} joints deep")
      for argv in (["loads"], ["design", "show"])),
    # 7, 9: FIFOs and devices, refused before they are opened
    *(Case(f"{' '.join(argv)} on {what}", files, argv, f"{name} is {kind}, not a regular file")
      for what, files, argv, name, kind in (
          ("a FIFO", {"r.urdf": FIFO}, ["design", "show", "--urdf", "r.urdf"], "r.urdf",
           "a FIFO"),
          ("a FIFO", {"r.urdf": FIFO}, ["explore", "--urdf", "r.urdf"], "r.urdf", "a FIFO"),
          ("a FIFO", {"r.urdf": FIFO, "d.toml": ROBOT_TABLE.format("r.urdf")},
           ["design", "show", "--design", "d.toml"], "r.urdf", "a FIFO"),
          ("a FIFO", {"top.xacro": XACRO.format(name="r", body=INCLUDE), "in.xacro": FIFO},
           ["loads", "--urdf", "top.xacro"], "in.xacro", "a FIFO"),
          ("a FIFO", {"top.xacro": XACRO.format(name="${xacro.load_yaml('y.yaml')}", body=""),
                      "y.yaml": FIFO}, ["loads", "--urdf", "top.xacro"], "y.yaml", "a FIFO"),
          ("/dev/zero", {}, ["design", "show", "--urdf", "/dev/zero"], "/dev/zero",
           "a character device"),
          ("/dev/urandom", {}, ["loads", "--urdf", "/dev/urandom"], "/dev/urandom",
           "a character device"),
          ("/dev/zero", {"d.toml": ROBOT_TABLE.format("/dev/zero")},
           ["design", "show", "--design", "d.toml"], "/dev/zero", "a character device"),
      )),
    # 8: Xacro nesting without end: Python's recursion limit, in the Xacro process
    *(Case(f"xacro: {what}", {"top.xacro": XACRO.format(name="r", body=body)},
           ["design", "show", "--urdf", "top.xacro"],
           "xacro on top.xacro nests macros or includes deeper than Python's recursion limit")
      for what, body in (
          ("a macro calling itself", '<xacro:macro name="m"><xacro:m/></xacro:macro><xacro:m/>'),
          ("a file including itself", '<xacro:include filename="top.xacro"/>'),
      )),
    Case("a robot file over the size cap", {"big.urdf": Sparse(source.MAX_ROBOT_FILE_BYTES + 1)},
         ["design", "show", "--urdf", "big.urdf"], "big.urdf is 16 MiB, larger than 16 MiB"),
    # 10: a huge mesh, refused by its size before any library reads it
    *(Case(f"{' '.join(argv)}: a 3 GiB mesh", {"k.urdf": KRABY, "meshes/box.stl": Sparse(HUGE)},
           [*argv, "--urdf", "k.urdf"], "mesh meshes/box.stl is 3 GiB, larger than 64 MiB")
      for argv in (["view", "--html", "v.html"], ["flexibility", "--collisions"])),
    # 20: a mesh coal cannot read: one line; numbers too large for a robot: no overflow warning
    Case("flexibility --collisions: a mesh that is no STL",
         {"k.urdf": KRABY, "meshes/box.stl": "solid nothing\n" + "garbage " * 100},
         ["flexibility", "--collisions", "--urdf", "k.urdf"],
         "the file's collision geometry cannot be read: "),
    Case("an origin of 1e308 m", {"o.urdf": kraby(FIRST_ORIGIN, 'xyz="1e308 0 0.2"')},
         ["design", "show", "--urdf", "o.urdf"],
         "joint 'fixed_box_servomotor_0' origin xyz = '1e308 0 0.2' is not valid: each within "
         "±10000 [m]"),
    Case("a mass of 1e300 kg", {"o.urdf": kraby('<mass value="0.667" />', '<mass value="1e300"/>')},
         ["loads", "--urdf", "o.urdf"],
         "link 'box' inertial mass = 1e+300 is not valid: at most 1e+06 [kg]"),
]  # fmt: skip

SIMULATE_CASES = [
    Case("simulate: a moving link without mass",
         {"z.urdf": kraby('<mass value="0.011" />', '<mass value="0" />')},
         ["simulate", "--urdf", "z.urdf", "--stride", "0.02", "--step-height", "0.01"],
         "MuJoCo cannot simulate link 'joint_0': mass and inertia of moving "
         "bodies must be larger than mjMINVAL"),
    Case("simulate: an inertia no body has",
         {"i.urdf": kraby('ixx="0.000269"', 'ixx="5"')},
         ["simulate", "--urdf", "i.urdf", "--stride", "0.02", "--step-height", "0.01"],
         "MuJoCo cannot simulate link 'servomotor_0': inertia must satisfy "
         "A + B >= C"),
    Case("simulate of a file without masses", {"m.urdf": MASSLESS},
         ["simulate", "--urdf", "m.urdf"], NO_MASSES),
]  # fmt: skip


@pytest.mark.parametrize("case", CASES, ids=[case.name for case in CASES])
def test_a_hostile_robot_file_ends_in_one_line(tmp_path, monkeypatch, case):
    _check(case, tmp_path, monkeypatch)


@pytest.mark.parametrize("case", SIMULATE_CASES, ids=[case.name for case in SIMULATE_CASES])
def test_a_robot_mujoco_refuses_ends_in_one_line(tmp_path, monkeypatch, case):
    pytest.importorskip("mujoco")
    _check(case, tmp_path, monkeypatch)


HOSTILE_XACRO = {
    "a power tower": XACRO.format(name="${9**9**9}", body=""),
    "a string doubled 64 times": XACRO.format(
        name="r", body='<xacro:property name="s0" value="ab"/>' + DOUBLING + '<link name="${s64}"/>'
    ),
    "macros nested 2**40 times": XACRO.format(name="r", body=NESTED + "<xacro:m40/>"),
}


@pytest.mark.slow  # each runs into its limit (seconds), or draws the scene
@pytest.mark.parametrize("name", HOSTILE_XACRO)
def test_hostile_xacro_is_stopped_at_its_limits(tmp_path, monkeypatch, name):
    monkeypatch.setattr(source, "XACRO_SECONDS", 1.0)
    case = Case(name, {"top.xacro": HOSTILE_XACRO[name]}, ["design", "show", "--urdf", "top.xacro"],
                "xacro on top.xacro ")  # fmt: skip
    started = time.monotonic()
    _check(case, tmp_path, monkeypatch)
    assert time.monotonic() - started < 1.0 + 10.0  # its limit, and the command around it


@pytest.mark.slow  # each runs into its limit (seconds), or draws the scene
def test_xacro_past_its_memory_limit_is_one_line(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(source, "XACRO_MEMORY_BYTES", 256 * 2**20)
    (tmp_path / "top.xacro").write_text(HOSTILE_XACRO["a string doubled 64 times"])
    assert run_cli(["design", "show", "--urdf", str(tmp_path / "top.xacro")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "more than the 256 MiB of memory" in err, err


def test_a_tree_at_the_depth_limit_builds_in_pinocchio(tmp_path):
    """The limit leaves Pinocchio's recursive parser room (its crash is a SIGSEGV: in a child)."""
    path = tmp_path / "deep.urdf"
    path.write_text(deep(MAX_TREE_DEPTH))  # the chain's last link: MAX_TREE_DEPTH deep
    build = (
        "import sys, pinocchio as pin; "
        "m = pin.buildModelFromXML(open(sys.argv[1]).read(), pin.JointModelFreeFlyer()); "
        "print(m.nframes)"
    )
    done = subprocess.run([sys.executable, "-c", build, str(path)], capture_output=True, text=True,
                          timeout=120)  # fmt: skip
    assert done.returncode == 0, done.stderr[-500:]
    assert int(done.stdout) > MAX_TREE_DEPTH


def test_internal_entities_read_as_the_plain_file(tmp_path, capsys):
    """XML's own entities are expanded; the oracle: Kraby written without them."""
    with_entities = (
        KRABY.replace(
            '<?xml version="1.0" ?>',
            '<?xml version="1.0" ?>\n<!DOCTYPE robot [<!ENTITY e "1.18"><!ENTITY m "0.667">]>',
        )
        .replace('effort="1.18"', 'effort="&e;"')
        .replace('value="0.667"', 'value="&m;"')
    )
    assert with_entities.count("&e;") == 18
    (tmp_path / "e.urdf").write_text(with_entities)
    (tmp_path / "k.urdf").write_text(KRABY)
    answers = []
    for name in ("e.urdf", "k.urdf"):
        assert run_cli(["loads", "--urdf", str(tmp_path / name), "--json"]) == 0
        answer = json.loads(capsys.readouterr().out)
        answers.append((answer["payload_capacity"], answer["mass"], answer["nominal"]))
    assert answers[0] == answers[1]


NAMES = ['foot"0', "foot<0", "foot&0", 'foot_0"/><child link="evil']
"""Names of leg 0's tibia link: quotes, markup and what injects elements if pasted unescaped."""


@pytest.mark.parametrize("name", NAMES)
def test_urdf_writes_any_link_name_as_xml(tmp_path, capsys, name):
    """Oracle: the XML parser reads back each added foot joint's parent as the file's name."""
    (tmp_path / "q.urdf").write_text(renamed("foot_0", name))
    out = tmp_path / "out.urdf"
    assert run_cli(["urdf", "--urdf", str(tmp_path / "q.urdf"), "-o", str(out)]) == 0
    root = ET.parse(out).getroot()
    feet = {
        j.get("name"): j for j in root.iter("joint") if j.get("name", "").endswith("_foot_joint")
    }
    assert len(feet) == 6
    parents = sorted(j.find("parent").get("link") for j in feet.values())
    assert name in parents
    assert all(len(j.findall("parent")) == len(j.findall("child")) == 1 for j in feet.values())
    assert not any(link.get("name") == "evil" for link in root.iter("link"))
    assert run_cli(["loads", "--urdf", str(tmp_path / "q.urdf")]) == 0  # Pinocchio reads it too
    capsys.readouterr()


KINEMATIC = {
    "workspace": (["workspace", "--samples", "300"], lambda a: a["legs"]),
    "manipulability": (["manipulability"], lambda a: a["legs"]),
    "flexibility": (["flexibility"], lambda a: (a["fb"], a["ranges"], a["extremes"])),
    "design show": (
        ["design", "show"],
        lambda a: [
            {k: v for k, v in leg.items() if k != "segment_masses"} for leg in a["design"]["legs"]
        ],
    ),
}


@pytest.mark.parametrize("command", KINEMATIC)
def test_a_file_without_masses_answers_kinematics_as_the_file_with_them(tmp_path, capsys, command):
    """Oracle: the same commands on Kraby with its masses (kinematics do not depend on them)."""
    argv, part = KINEMATIC[command]
    (tmp_path / "m.urdf").write_text(MASSLESS)
    (tmp_path / "k.urdf").write_text(KRABY)
    answers = []
    for name in ("m.urdf", "k.urdf"):
        assert run_cli([*argv, "--urdf", str(tmp_path / name), "--json"]) == 0
        answers.append(part(json.loads(capsys.readouterr().out)))
    assert answers[0] == answers[1]


def test_design_show_of_a_file_without_masses_says_it_has_none(tmp_path, capsys):
    (tmp_path / "m.urdf").write_text(MASSLESS)
    assert run_cli(["design", "show", "--urdf", str(tmp_path / "m.urdf")]) == 0
    mass = [line for line in capsys.readouterr().out.splitlines() if "mass" in line.split()[:1]]
    assert len(mass) == 1 and "none: the file gives no masses (kinematics only)" in mass[0]


@pytest.mark.slow  # each runs into its limit (seconds), or draws the scene
def test_a_file_without_masses_is_viewed_uncoloured_and_written(tmp_path, capsys):
    (tmp_path / "m.urdf").write_text(MASSLESS)
    assert (
        run_cli(["view", "--urdf", str(tmp_path / "m.urdf"), "--html", str(tmp_path / "v.html")])
        == 0
    )
    assert (
        run_cli(["urdf", "--urdf", str(tmp_path / "m.urdf"), "-o", str(tmp_path / "u.urdf")]) == 0
    )
    written = ET.parse(tmp_path / "u.urdf").getroot()
    assert not list(written.iter("inertial"))  # the file's own, with its feet: still no masses
    err = capsys.readouterr().err
    assert "nan" not in err and "10000" not in err
    assert (tmp_path / "v.html").stat().st_size > 0


def test_explore_refuses_a_file_without_masses_before_serving(tmp_path, monkeypatch, capsys):
    served = []
    monkeypatch.setattr("hexaleg.explore.server.ExplorerServer", lambda *a: served.append(a))
    (tmp_path / "m.urdf").write_text(MASSLESS)
    monkeypatch.chdir(tmp_path)
    assert run_cli(["explore", "--urdf", "m.urdf"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and NO_MASSES in err and not served


def test_a_mesh_at_the_cap_is_read_and_one_past_it_refused(tmp_path, monkeypatch):
    """The cap is on the file's size: exactly the cap passes, one byte more does not."""
    from hexaleg.exceptions import RobotImportError

    mesh = tmp_path / "m.stl"
    with mesh.open("wb") as file:
        file.truncate(1000)
    monkeypatch.setattr(source, "MAX_MESH_BYTES", 1000)
    assert source.check_mesh_file(mesh, "m.stl") == 1000
    monkeypatch.setattr(source, "MAX_MESH_BYTES", 999)
    with pytest.raises(RobotImportError, match=r"mesh m\.stl is 1000 bytes, larger than 999 bytes"):
        source.check_mesh_file(mesh, "m.stl")


def test_xacro_past_its_output_cap_is_one_line(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(source, "MAX_ROBOT_FILE_BYTES", 20_000)
    links = '<xacro:macro name="l" params="i"><link name="link${i}"/></xacro:macro>'
    many = "".join(f'<xacro:l i="{i}"/>' for i in range(1000))  # about 24 kB of URDF
    (tmp_path / "top.xacro").write_text(XACRO.format(name="r", body=links + many))
    assert (tmp_path / "top.xacro").stat().st_size < 20_000
    assert run_cli(["design", "show", "--urdf", str(tmp_path / "top.xacro")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "xacro on top.xacro writes more than 19.5 KiB of URDF" in err


@pytest.mark.parametrize(
    "path", ["phantomx_kevinochs/urdf/phantomX_model.xacro", "golem_4dof/urdf/hexapod_model.xacro"]
)
def test_xacro_in_its_limited_process_expands_as_xacro_itself(path):
    """Oracle: the xacro package run in this process, without limits, on the same file."""
    import xacro

    expected = xacro.process_file(str(ROBOTS / path)).toxml()
    started = time.monotonic()
    assert source.read_robot_text(ROBOTS / path) == expected
    assert time.monotonic() - started < 5.0
