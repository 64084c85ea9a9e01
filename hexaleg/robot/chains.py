"""The legs of a robot file: six chains of three revolute joints hanging from the body.

The body is the root link with every link fixed to it. Each movable joint whose parent
is on the body starts a chain; the chain follows the one movable joint of each link group
(links held together by fixed joints) out to the last. A chain of three revolute (or
continuous) joints is a leg; a shorter one (a pan-tilt head, a sensor mount) is locked at
q = 0 and weighs as part of the body. Beyond a leg's third revolute joint, a joint that is
not the leg's — a prismatic one (a foot-contact sensor), or one whose range is below
:data:`LOCKED_RANGE` — is locked at q = 0 and moves with the tibia; anything else is refused
in one line naming what was found. Joints the caller locks (glob patterns) count as fixed
everywhere.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from fnmatch import fnmatchcase

from hexaleg.exceptions import RobotImportError
from hexaleg.robot.description import Joint, RobotDescription

LEG_COUNT = 6
"""Legs of a hexapod."""

LEG_JOINT_COUNT = 3
"""Revolute joints of a yaw–pitch–pitch leg."""

REVOLUTE = ("revolute", "continuous")

LOCKED_RANGE = {"revolute": 0.01, "prismatic": 1e-3}
"""A joint beyond a leg's third whose range (upper − lower) is below this is no joint of the
leg but a part of the tibia: locked at q = 0 [rad, m]. A prismatic one is always locked."""


@dataclass(frozen=True)
class LegChain:
    """One leg as the file draws it.

    Attributes:
        joints: Its three joints, from the body out (yaw, hip, knee).
        segments: Each joint's moving links: its child link first, then every link
            fixed to it (before the next joint).

    """

    joints: tuple[Joint, Joint, Joint]
    segments: tuple[tuple[str, ...], tuple[str, ...], tuple[str, ...]]


@dataclass(frozen=True)
class Chains:
    """A robot file's legs and what was locked to find them.

    Attributes:
        legs: The six legs, in the file's order.
        body: The body's links: the root link and every link fixed (or locked) to it.
        locked: Every movable joint treated as fixed: the caller's, then the short chains',
            then those beyond a leg's knee.
        accessories: The short chains' joints (a subset of ``locked``).
        beyond: The joints beyond a leg's knee locked as parts of its tibia (a subset of
            ``locked``): prismatic ones and those of a range below :data:`LOCKED_RANGE`.

    """

    legs: tuple[LegChain, ...]
    body: tuple[str, ...]
    locked: tuple[str, ...]
    accessories: tuple[str, ...]
    beyond: tuple[str, ...] = ()


def find_chains(description: RobotDescription, lock: Sequence[str] = ()) -> Chains:
    """The six legs of ``description``, with the joints matching ``lock`` held fixed.

    Raises:
        RobotImportError: A lock pattern matches no joint, a chain branches, has more than
            three movable joints or one that is not revolute, or there are not six legs.

    """
    asked = _locked(description, lock)
    locked = set(asked)
    beyond: list[str] = []
    legs: list[LegChain] = []
    accessories: list[str] = []
    for start in _chain_starts(description, locked):
        joints, segments = _follow(description, start, locked)
        while len(joints) > LEG_JOINT_COUNT and not_the_legs(joints[LEG_JOINT_COUNT]):
            beyond.append(joints[LEG_JOINT_COUNT].name)
            locked.add(beyond[-1])
            joints, segments = _follow(description, start, locked)
        if len(joints) < LEG_JOINT_COUNT:
            accessories += [j.name for j in joints]
            continue
        _check_leg(joints)
        legs.append(
            LegChain((joints[0], joints[1], joints[2]), (segments[0], segments[1], segments[2]))
        )
    if len(legs) != LEG_COUNT:
        firsts = ", ".join(leg.joints[0].name for leg in legs[:8]) + (
            ", ..." if len(legs) > 8 else ""
        )
        found = f"found {len(legs)} legs of 3 revolute joints"
        raise RobotImportError(
            f"{found}{f' (from joints {firsts})' if legs else ''}; a hexapod has {LEG_COUNT}"
        )
    locked |= set(accessories)
    body = _group(description, description.root, locked)
    return Chains(
        tuple(legs),
        body,
        tuple(asked) + tuple(accessories) + tuple(beyond),
        tuple(accessories),
        tuple(beyond),
    )


def not_the_legs(joint: Joint) -> bool:
    """Whether a joint beyond a leg's knee is a part of its tibia: prismatic, or barely moving."""
    if joint.kind == "prismatic":
        return True
    smallest = LOCKED_RANGE.get(joint.kind)
    return smallest is not None and joint.upper - joint.lower < smallest


def _locked(description: RobotDescription, patterns: Sequence[str]) -> list[str]:
    """The movable joints matching any of ``patterns``, in the file's order."""
    if isinstance(patterns, str):
        patterns = (patterns,)
    names = [name for name, joint in description.joints.items() if joint.movable]
    for pattern in patterns:
        if not any(fnmatchcase(name, pattern) for name in names):
            raise RobotImportError(f"lock pattern {pattern!r} matches no movable joint")
    return [n for n in names if any(fnmatchcase(n, p) for p in patterns)]


def _moves(joint: Joint, locked: set[str]) -> bool:
    return joint.movable and joint.name not in locked


def _group(description: RobotDescription, link: str, locked: set[str]) -> tuple[str, ...]:
    """``link`` and every link held to it by fixed (or locked) joints, parents first."""
    group, stack = [link], [link]
    while stack:
        for joint in description.children[stack.pop()]:
            if not _moves(joint, locked):
                group.append(joint.child)
                stack.append(joint.child)
    return tuple(group)


def _chain_starts(description: RobotDescription, locked: set[str]) -> list[Joint]:
    """The movable joints whose parent is on the body, in the file's order."""
    body = set(_group(description, description.root, locked))
    return [j for j in description.joints.values() if j.parent in body and _moves(j, locked)]


def _follow(
    description: RobotDescription, start: Joint, locked: set[str]
) -> tuple[list[Joint], list[tuple[str, ...]]]:
    """The movable joints of the chain from ``start`` and each one's moving links."""
    joints, segments = [start], []
    while True:
        group = _group(description, joints[-1].child, locked)
        segments.append(group)
        nxt = [j for link in group for j in description.children[link] if _moves(j, locked)]
        if len(nxt) > 1:
            names = ", ".join(j.name for j in nxt)
            raise RobotImportError(
                f"leg from joint {start.name} branches after joint {joints[-1].name}: "
                f"joints {names} all move (lock the ones that are not the leg's: --lock-joint NAME)"
            )
        if not nxt:
            return joints, segments
        joints.append(nxt[0])


def _check_leg(joints: list[Joint]) -> None:
    """Refuse a chain of three or more joints that is not three revolute ones."""
    start = joints[0].name
    other = [j for j in joints if j.kind not in REVOLUTE]
    if other:
        j = other[0]
        raise RobotImportError(
            f"leg from joint {start} has a {j.kind} joint {j.name}: lock it at its zero "
            f"with --lock-joint {j.name} (lock_joints in [robot])"
        )
    if len(joints) > LEG_JOINT_COUNT:
        names = ", ".join(j.name for j in joints)
        raise RobotImportError(
            f"leg from joint {start} has {len(joints)} revolute joints ({names}); "
            f"a yaw-pitch-pitch leg has {LEG_JOINT_COUNT} (--lock-joint NAME holds one at its "
            f"zero)"
        )
