"""Design studies: many designs in tasks, on any ``concurrent.futures.Executor``.

A study sweeps coxa and tibia ratios at a fixed total leg length (Fig 14–15),
keeping every other field of a base design. Each finished row is appended to a
journal (``rows.jsonl``) and flushed to disk as its task finishes, so an interrupted
study loses nothing: :func:`run_study` with ``resume=True`` recomputes only the
missing rows. A design that fails (say, its nominal stance cannot stand) is
recorded with its error and the study goes on. The journal's rules (torn lines, corrupt
lines, a full disk) are in :mod:`hexaleg.study.journal`; one run at a time holds the
study folder.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Iterable, Mapping
from concurrent.futures import Executor, as_completed
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Any

import pandas as pd

from hexaleg._folders import claim_folder, lock_folder
from hexaleg._io import write_text
from hexaleg._typing import FlexibilityMode, StanceSet, require_choice
from hexaleg.design import (
    DEFAULT_LEG_LENGTH,
    MAX_L3_POINTS,
    SEGMENT_RANGE,
    SEGMENTS,
    HexapodDesign,
    require_in_range,
    require_ratio,
)
from hexaleg.evaluation.evaluate import Conditions, evaluate, evaluate_many
from hexaleg.evaluation.metrics import METRICS, MetricSpec
from hexaleg.evaluation.walks import walking_grounds
from hexaleg.exceptions import HexalegError
from hexaleg.gait.analysis import STUDY_GAIT
from hexaleg.gait.spec import Gait
from hexaleg.ratios import MAX_L1_RATIOS, require_ratio_grid
from hexaleg.robot.model import HexapodModel
from hexaleg.robot.robot import Robot, template_robot
from hexaleg.stance.geometry import StanceGeometry
from hexaleg.study.executors import local_pool, worker_failures
from hexaleg.study.journal import (
    FOLDER_KIND,
    JOURNAL,
    adopt_unmarked_study,
    append_rows,
    start_journal,
    write_finished_journal,
)
from hexaleg.study.progress import Progress
from hexaleg.study.rows import Key, StudyRow, study_row, walking_metrics

TABLE_CSV = "study.csv"
TABLE_JSON = "study.json"


@dataclass(frozen=True)
class StudySpec:
    """What a study computes.

    Attributes:
        l1_ratios: Coxa ratios l1/L [-].
        l3_ratios: Tibia ratios l3/L [-].
        total: Total leg length L [m].
        mode: ``"axis"`` (axis-locked) or ``"free"`` (free-coupled) flexibility.
        stance: ``"all"`` or ``"tripod"``.
        base: Every other field of the designs (body, mounts, posture, limits).
        collisions: The robot's own parts touching also stop the body.
        statics: Also compute each design's torques, stability, slopes and payload.
        gait: Also compute each design's walking columns, walking ``walked``.
        walked: The gait every design walks: the design file's ``[gait]`` table, else
            :data:`~hexaleg.gait.analysis.STUDY_GAIT` (the default gait).
        robot: The robot whose designs these are, each at a row's segment lengths
            (:meth:`~hexaleg.robot.robot.Robot.at`); hexaleg's template over ``base`` if
            not given. It reaches workers as its recipe.
        walking_slope: The slope every design walks ``walked`` up, down and across, as a
            requirement's ``walking_slope`` asks [rad] (0: level ground).
        safety_factor: The motors' safety factor the walks hold their ratings by [-].

    """

    l1_ratios: tuple[float, ...]
    l3_ratios: tuple[float, ...]
    total: float = DEFAULT_LEG_LENGTH
    mode: FlexibilityMode = "axis"
    stance: StanceSet = "all"
    base: HexapodDesign = field(default_factory=HexapodDesign)
    collisions: bool = False
    statics: bool = True
    gait: bool = True
    walked: Gait = STUDY_GAIT
    robot: Robot = None  # type: ignore[assignment]  # hexaleg's template over base
    walking_slope: float = 0.0
    safety_factor: float = 1.0

    def __post_init__(self) -> None:
        if self.robot is None:
            object.__setattr__(self, "robot", template_robot(self.base))
        object.__setattr__(self, "l1_ratios", tuple(float(r) for r in self.l1_ratios))
        object.__setattr__(self, "l3_ratios", tuple(float(r) for r in self.l3_ratios))
        require_choice("mode", self.mode, FlexibilityMode)
        require_choice("stance", self.stance, StanceSet)
        if not self.l1_ratios or not self.l3_ratios:
            raise HexalegError("a study needs at least one coxa ratio and one tibia ratio")
        if len(self.l1_ratios) > MAX_L1_RATIOS or len(self.l3_ratios) > MAX_L3_POINTS:
            raise HexalegError(
                f"a study takes at most {MAX_L1_RATIOS} coxa ratios and {MAX_L3_POINTS} "
                f"tibia ratios (given {len(self.l1_ratios)} and {len(self.l3_ratios)})"
            )
        for r1 in self.l1_ratios:
            require_ratio("l1_ratios", r1)
        for r3 in self.l3_ratios:
            require_ratio("l3_ratios", r3)
        require_in_range("total", self.total, 3 * SEGMENT_RANGE[0], 3 * SEGMENT_RANGE[1], "m")
        require_in_range("walking_slope", self.walking_slope, 0.0, math.pi / 2, "rad")
        require_in_range("safety_factor", self.safety_factor, 1.0, math.inf, "")
        require_ratio_grid(self.l1_ratios, self.l3_ratios, self.total)  # no design fails

    @property
    def metrics(self) -> tuple[MetricSpec, ...]:
        """What each design is measured for: FB, and the statics' and the gait's if asked.

        The metrics through the motors only when the designs have actuators.
        """
        standing = (METRICS.payload_capacity, METRICS.stability_margin) if self.statics else ()
        walking = walking_metrics(self.base) if self.gait else ()
        return (METRICS.fb, *standing, *walking)

    @property
    def conditions(self) -> Conditions:
        """What each design is measured under: no payload, walking :attr:`walked`.

        Standing on level ground; walking on the grounds of :attr:`walking_slope`.
        """
        return Conditions(
            gait=self.walked,
            stance=self.stance,
            mode=self.mode,
            collisions=self.collisions,
            keep=True,
            grounds=walking_grounds(self.walking_slope, self.walked),
            safety_factor=self.safety_factor,
        )

    def row_of(self, robot: Robot) -> StudyRow:
        """``robot``'s row (a design of the study's, or the user's), measured as the study's."""
        design = robot.design
        key = (design.l1 / design.leg_length, design.l3 / design.leg_length)
        evaluation = evaluate(design, self.metrics, self.conditions, model=robot.model)
        return study_row(key, design, evaluation)

    def keys(self) -> list[Key]:
        """(l1 ratio, l3 ratio) of every design, in table order."""
        return [(r1, r3) for r1 in self.l1_ratios for r3 in self.l3_ratios]

    def fingerprint(self) -> dict[str, Any]:
        """Everything that determines the results, JSON-ready (checked on resume)."""
        return {
            "l1_ratios": list(self.l1_ratios),
            "l3_ratios": list(self.l3_ratios),
            "total": self.total,
            "mode": self.mode,
            "stance": self.stance,
            "collisions": self.collisions,
            "statics": self.statics,
            "gait": self.gait,
            **({} if self.walked == STUDY_GAIT else {"walked": self.walked.to_dict()}),
            **({} if not self.walking_slope else {"walking_slope": self.walking_slope}),
            **({} if self.safety_factor == 1 else {"safety_factor": self.safety_factor}),
            "base": {k: v for k, v in self.base.as_dict().items() if k not in SEGMENTS},
            **self.robot.fingerprint(),
        }


CHUNK = 8
"""Designs per task: the axis-locked search runs them together (a third less time per
design than one by one), and two workers still share 320 designs evenly."""


@dataclass(frozen=True)
class _Task:
    keys: tuple[Key, ...]  # (l1 ratio, l3 ratio) of each design
    spec: StudySpec
    template: StanceGeometry | None  # the robot's body's, read once (None: legs of its own)


def evaluate_task(task: _Task) -> list[StudyRow]:
    """The rows of a task's designs; a design's error becomes its row's ``error``.

    Each design is the study's robot at the row's segment lengths.
    """
    spec = task.spec
    points: dict[Key, Robot] = {}
    rows: dict[Key, StudyRow] = {}
    for key in task.keys:
        try:
            points[key] = spec.robot.at_ratios(key[0], key[1], spec.total)
        except HexalegError as err:
            rows[key] = StudyRow(*key, error=str(err))
    robots = list(points.values())
    designs, models = [r.design for r in robots], [r.model for r in robots]
    found = evaluate_many(designs, spec.metrics, spec.conditions, models, task.template)
    for (key, point), evaluation in zip(points.items(), found, strict=True):
        rows[key] = study_row(key, point.design, evaluation)
    return [rows[key] for key in task.keys]


def sweep(
    spec: StudySpec,
    executor: Executor,
    skip: Iterable[Key] = (),
    on_rows: Callable[[list[StudyRow]], None] | None = None,
) -> dict[Key, StudyRow]:
    """Evaluate every design of ``spec`` not in ``skip`` on ``executor``; rows by ratio pair.

    ``on_rows`` sees each task's rows as they arrive (the journal and the progress bar
    use it).
    """
    done = set(skip)
    rows: dict[Key, StudyRow] = {}
    with worker_failures():
        futures = [
            executor.submit(evaluate_task, task)
            for task in _tasks(spec, [key for key in spec.keys() if key not in done])
        ]
        for future in as_completed(futures):
            finished = future.result()
            rows |= {row.key: row for row in finished}
            if on_rows is not None:
                on_rows(finished)
    return rows


@lru_cache(maxsize=4)
def base_model(base: HexapodDesign) -> HexapodModel:
    """The base design's Pinocchio model, built once per process.

    Each design of a study derives its own from it (:meth:`HexapodModel.with_design`).
    It is sent to no worker: a pickled model is 2 MB and 70 ms each way.
    """
    return HexapodModel(base)


def _tasks(spec: StudySpec, keys: list[tuple[float, float]]) -> list[_Task]:
    """The designs ``keys`` in tasks: :data:`CHUNK` per axis-locked search, free ones alone.

    A free-coupled design takes a few tenths of a second, so it is a task of its own.
    """
    template = StanceGeometry.template_of(spec.robot.model, spec.stance)
    size = CHUNK if spec.mode == "axis" else 1
    return [_Task(tuple(keys[i : i + size]), spec, template) for i in range(0, len(keys), size)]


def sweep_in_process(spec: StudySpec, known: Mapping[Key, StudyRow] | None = None) -> pd.DataFrame:
    """The whole study evaluated in this process, as a table (for small, fast studies).

    ``known``: rows already measured, by key: not measured again.
    """
    known = known or {}
    keys = [key for key in spec.keys() if key not in known]
    rows = [row for task in _tasks(spec, keys) for row in evaluate_task(task)]
    return study_table(spec, {**known, **{row.key: row for row in rows}})


def run_study(
    spec: StudySpec,
    out_dir: str | os.PathLike[str],
    executor: Executor | None = None,
    workers: int | None = None,
    resume: bool = False,
    progress: bool | None = None,
) -> pd.DataFrame:
    """Run (or resume) a study and write its table; return it as a pandas DataFrame.

    Args:
        spec: What to compute.
        out_dir: Folder for the journal, ``study.csv`` and ``study.json``: new, empty, or
            a study folder hexaleg wrote; held (locked) by this run until it returns.
        executor: Where tasks run; a local process pool of ``workers`` if omitted.
        workers: Size of the local pool (default: the number of CPUs).
        resume: Continue the journal in ``out_dir`` instead of refusing to overwrite it.
        progress: ``False`` shows nothing; otherwise a bar on stderr if it is a terminal,
            else a line every few seconds (:class:`~hexaleg.study.progress.Progress`).

    Raises:
        HexalegError: ``out_dir`` is not a study folder, is in use by another run, holds
            a study with other options or a corrupt journal; a journal write failed; the
            statics or the gait asked of a robot without masses (before any folder is
            touched).

    """
    if spec.statics or spec.gait:
        spec.robot.require_masses()
    adopt_unmarked_study(out_dir)
    out = claim_folder(out_dir, FOLDER_KIND)
    with lock_folder(out, "study"):
        kept = start_journal(out, spec.fingerprint(), spec.keys(), resume)
        done = {key: StudyRow.from_dict(record) for key, record in kept.items()}
        with Progress(len(spec.keys()), len(done), "designs", progress) as shown:

            def record(rows: list[StudyRow]) -> None:
                append_rows(out / JOURNAL, [row.to_dict() for row in rows])
                shown.update(len(rows))

            if executor is None:
                with local_pool(workers) as pool:
                    done |= sweep(spec, pool, skip=done, on_rows=record)
            else:
                done |= sweep(spec, executor, skip=done, on_rows=record)
        return write_table(spec, study_table(spec, done), out)


def study_table(spec: StudySpec, rows: Mapping[Key, StudyRow]) -> pd.DataFrame:
    """The rows of a finished sweep as a table, in (coxa, tibia) ratio order."""
    table = pd.DataFrame([rows[key].to_dict() for key in spec.keys()])
    return table.sort_values(["l1_ratio", "l3_ratio"], kind="stable").reset_index(drop=True)


def write_journal(out: Path, spec: StudySpec, table: pd.DataFrame) -> Path:
    """Write a finished study's journal (``rows.jsonl``) in one go, atomically."""
    return write_finished_journal(out, spec.fingerprint(), table.to_dict(orient="records"))


def write_table(spec: StudySpec, table: pd.DataFrame, out: Path) -> pd.DataFrame:
    """Write ``study.csv`` and ``study.json`` atomically; return ``table``."""
    write_text(out / TABLE_CSV, table.to_csv(index=False))
    payload = {
        "spec": spec.fingerprint(),
        "units": {
            "ratios": "1",
            "lengths and x y z": "m",
            "roll pitch yaw": "rad",
            METRICS.fb.name: METRICS.fb.unit,
        },
        "peaks": peak_table(table).to_dict(orient="records"),
        "rows": json.loads(table.to_json(orient="records")),
    }
    write_text(out / TABLE_JSON, json.dumps(payload, indent=1))
    return table


def peak_table(table: pd.DataFrame) -> pd.DataFrame:
    """For each coxa ratio, the tibia ratio of the largest FB and that FB."""
    rows = []
    fb = METRICS.fb.name
    for r1, group in table.groupby("l1_ratio", sort=True):
        valid = group.dropna(subset=[fb]) if fb in group else group.iloc[0:0]
        if valid.empty:
            rows.append({"l1_ratio": r1, "peak_l3_ratio": math.nan, "peak_fb": math.nan})
            continue
        best = valid.loc[valid[fb].idxmax()]
        rows.append({"l1_ratio": r1, "peak_l3_ratio": best["l3_ratio"], "peak_fb": best[fb]})
    return pd.DataFrame(rows)
