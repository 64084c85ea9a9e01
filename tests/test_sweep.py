"""Design studies: local pool, Dask on loopback, failures recorded, kill and resume."""

from __future__ import annotations

import json
import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np
import pandas as pd
import pytest
from conftest import kill_hexaleg_when, run_cli

from hexaleg import HexapodDesign
from hexaleg.cli import main
from hexaleg.exceptions import HexalegError
from hexaleg.stance import flexibility
from hexaleg.study import StudySpec, peak_table, run_study, sensitivity_table
from hexaleg.study.sweep import JOURNAL

SMALL = StudySpec((0.05, 0.2), tuple(np.linspace(0.1, 0.7, 7)))


def test_study_rows_equal_single_design_results(tmp_path):
    table = run_study(SMALL, tmp_path, executor=ThreadPoolExecutor(2))
    assert len(table) == 14 and (table["error"] == "").all()
    row = table.iloc[3]
    single = flexibility(HexapodDesign.from_ratios(row["l1_ratio"], row["l3_ratio"]), "axis", "all")
    assert row["fb"] == pytest.approx(single.fb, rel=1e-12)
    assert row["range_x"] == pytest.approx(single.ranges["x"], rel=1e-12)
    assert row["x_max_limited_by"] == single.extreme("x", 1).description
    saved = pd.read_csv(tmp_path / "study.csv")
    assert len(saved) == 14
    payload = json.loads((tmp_path / "study.json").read_text())
    assert len(payload["rows"]) == 14 and len(payload["peaks"]) == 2


def test_local_process_pool_gives_the_same_table(tmp_path):
    threads = run_study(SMALL, tmp_path / "threads", executor=ThreadPoolExecutor(2))
    processes = run_study(SMALL, tmp_path / "processes", workers=2)
    pd.testing.assert_frame_equal(threads, processes)


def test_failing_design_is_recorded_and_the_study_goes_on(tmp_path):
    # hip raised with a short tibia: the feet end above the body's underside
    base = HexapodDesign(nominal_angles=(0.0, 0.5, -math.pi / 2 - 0.5))
    spec = StudySpec((0.1,), (0.1, 0.4), base=base)
    table = run_study(spec, tmp_path, executor=ThreadPoolExecutor(1))
    failed = table[table["error"] != ""]
    assert failed["l3_ratio"].tolist() == [0.1]
    assert "below the body" in failed["error"].iloc[0]
    assert math.isnan(failed["l1"].iloc[0])
    assert table[table["error"] == ""]["fb"].notna().all()


def test_an_existing_study_is_not_overwritten_without_resume(tmp_path):
    run_study(SMALL, tmp_path, executor=ThreadPoolExecutor(1))
    with pytest.raises(HexalegError, match="--resume"):
        run_study(SMALL, tmp_path, executor=ThreadPoolExecutor(1))
    other = StudySpec((0.1,), (0.3,))
    with pytest.raises(HexalegError, match="other options"):
        run_study(other, tmp_path, executor=ThreadPoolExecutor(1), resume=True)


def test_a_folder_that_is_not_a_study_is_left_alone(tmp_path, capsys):
    (tmp_path / "report.md").write_text("someone's report")
    with pytest.raises(HexalegError, match="not a hexaleg study"):
        run_study(SMALL, tmp_path, executor=ThreadPoolExecutor(1))
    assert main(["study", "--l3-points", "2", "-o", str(tmp_path)]) == 2
    assert capsys.readouterr().err.count("\n") == 1
    assert [p.name for p in tmp_path.iterdir()] == ["report.md"]


def test_resume_skips_finished_rows_and_survives_a_torn_line(tmp_path):
    full = run_study(SMALL, tmp_path / "full", executor=ThreadPoolExecutor(1))
    journal = (tmp_path / "full" / JOURNAL).read_text().splitlines()
    partial = tmp_path / "partial"
    partial.mkdir()
    # header + 5 rows + half a row, as a kill in the middle of a write leaves it
    (partial / JOURNAL).write_text("\n".join(journal[:6]) + "\n" + journal[6][:20])
    calls = []

    class CountingExecutor(ThreadPoolExecutor):
        def submit(self, fn, *args, **kwargs):
            calls.append(args)
            return super().submit(fn, *args, **kwargs)

    resumed = run_study(SMALL, partial, executor=CountingExecutor(1), resume=True)
    assert sum(len(task.keys) for task, *_ in calls) == 14 - 5  # only the missing designs
    pd.testing.assert_frame_equal(resumed, full)


@pytest.mark.slow  # a study killed mid-run, resumed, and run straight to compare
def test_killed_study_resumes_to_the_same_table(tmp_path):
    """Kill the CLI's whole process group mid-study, resume it, compare with a straight run."""
    out = tmp_path / "killed"
    argv = ["study", "--l1-ratios", "0.05", "0.1", "--l3-points", "300", "--workers", "1"]
    journal = out / JOURNAL

    def rows_written() -> bool:
        return journal.exists() and journal.read_text().count("\n") > 40

    kill_hexaleg_when([*argv, "-o", str(out)], rows_written, "the study")
    rows_at_kill = journal.read_text().count("\n") - 1
    assert 0 < rows_at_kill < 600
    assert not (out / "study.csv").exists()

    assert main([*argv, "-o", str(out), "--resume"]) == 0
    assert main([*argv, "-o", str(tmp_path / "straight")]) == 0
    assert (out / "study.csv").read_text() == (tmp_path / "straight" / "study.csv").read_text()


def test_dask_cluster_on_loopback(tmp_path, capsys):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=1,
        threads_per_worker=2,
        processes=False,
        host="127.0.0.1",
        scheduler_port=0,
        dashboard_address=None,
        protocol="tcp",
    ) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://127.0.0.1:")
        argv = ["study", "--l1-ratios", "0.1", "--l3-points", "6"]
        assert main([*argv, "--scheduler", address, "-o", str(tmp_path / "dask")]) == 0
    assert main([*argv, "--workers", "1", "-o", str(tmp_path / "local")]) == 0
    assert (tmp_path / "dask" / "study.csv").read_text() == (
        tmp_path / "local" / "study.csv"
    ).read_text()


@pytest.mark.slow  # Dask waits out its connect timeout (10 s)
def test_unreachable_scheduler_is_one_line(tmp_path, capsys):
    status = main(
        ["study", "--l3-points", "2", "--scheduler", "tcp://127.0.0.1:9", "-o", str(tmp_path / "s")]
    )
    assert status == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "scheduler" in err


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["--l1", "0.2"], "unrecognized arguments: --l1 0.2"),
        (["--workers", "0"], "--workers: 0 is not valid: must be >= 1"),
        (["--l3-points", "1"], "--l3-points: 1 is not valid: must be in 2..1000"),
        (["--l1-ratios", "0.9"], "must leave room for femur and tibia"),
        (["--l1-ratios", "0.8", "--l3-points", "3"], "l1_ratio + l3_ratio"),
    ],
)
def test_study_usage_errors(tmp_path, capsys, argv, expected):
    status = run_cli(["study", *argv, "-o", str(tmp_path / "s")])
    err = capsys.readouterr().err
    if "l1_ratio + l3_ratio" in expected:  # a design that cannot exist is a row, not an error
        assert status == 0
        table = pd.read_csv(tmp_path / "s" / "study.csv")
        failed = table[table["error"] != ""]
        assert failed["error"].str.contains(expected, regex=False).sum() == 2  # l3 0.425, 0.75
        return
    assert status == 2 and err.count("\n") == 1 and expected in err


def test_peak_table_and_sensitivity():
    table = pd.DataFrame(
        {"l1_ratio": [0.1, 0.1, 0.1], "l3_ratio": [0.2, 0.4, 0.6], "fb": [0.1, 0.3, 0.2]}
    )
    assert peak_table(table).to_dict(orient="records") == [
        {"l1_ratio": 0.1, "peak_l3_ratio": 0.4, "peak_fb": 0.3}
    ]
    sensitivity = sensitivity_table(
        (0.1,),
        tuple(np.linspace(0.2, 0.6, 5)),
        variants=(("default", {}), ("hip raised", {"nominal_angles": (0.0, 0.2, -1.77)})),
    )
    assert sensitivity["variant"].tolist() == ["default", "hip raised"]
    assert sensitivity["peak_fb"].notna().all()


@pytest.mark.filterwarnings("ignore::hexaleg.stance.extremes.FlexibilityWarning")
def test_free_study_rows_equal_single_design_results_without_rendering_each_urdf(monkeypatch):
    from hexaleg.robot import model as model_module
    from hexaleg.study.sweep import sweep_in_process

    rendered = []
    real_render = model_module.render_hexapod

    def counting_render(design):
        rendered.append(design)
        return real_render(design)

    monkeypatch.setattr(model_module, "render_hexapod", counting_render)
    spec = StudySpec((0.1,), (0.35, 0.45, 0.55), mode="free", statics=False)
    table = sweep_in_process(spec)
    # the study's base body is read once at most (it may be cached); its designs never
    assert all(design == spec.base for design in rendered) and len(rendered) <= 1
    for _, row in table.iterrows():
        single = flexibility(
            HexapodDesign.from_ratios(row["l1_ratio"], row["l3_ratio"]), "free", "all"
        )
        assert row["fb"] == pytest.approx(single.fb, rel=1e-9)
        assert row["z_min"] == pytest.approx(single.extreme("z", -1).value, rel=1e-9)
