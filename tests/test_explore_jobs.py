"""The explorer's long jobs: the free-coupled search and decide, beside the sliders.

A job is the command line in another process: its answer must be the command's own
(``flexibility --mode free --json`` run in-process is the oracle), its progress must come
in steps up to its total, the sliders must keep answering while it runs, and stopping it
must end its process (checked by its pid).
"""

from __future__ import annotations

import itertools
import json
import time

import psutil
import pytest
from explorer import running

from hexaleg.cli import main
from hexaleg.design import HexapodDesign
from hexaleg.stance.free_coupled import free_flexibility

pytestmark = pytest.mark.slow

JOB_TIMEOUT = 600
"""Bound on one job [s]."""


def _wait(server, kind: str) -> tuple[dict, list[dict]]:
    """Poll a job to its end (bounded); its last state and every state seen while running."""
    seen = []
    deadline = time.monotonic() + JOB_TIMEOUT
    while time.monotonic() < deadline:
        status, job = server.get(f"api/job?kind={kind}")
        assert status == 200
        if job["state"] != "running":
            return job, seen
        seen.append(job)
        time.sleep(0.3)
    pytest.fail(f"the {kind} job did not end within {JOB_TIMEOUT} s")


def test_the_free_coupled_job_answers_the_command_s_numbers_and_the_sliders_keep_answering(
    capsys,
):
    with running() as server:
        assert server.get("api/job?kind=free")[1]["state"] == "none"
        status, job = server.post("api/job?kind=free&l3=0.45")
        assert status == 200 and job["state"] == "running"
        status, meanwhile = server.get("api/evaluate?l3=0.44")  # a slider moved meanwhile
        assert status == 200 and meanwhile["fb"] > 0
        job, seen = _wait(server, "free")
    assert job["state"] == "done", job
    capsys.readouterr()
    assert main(["flexibility", "--mode", "free", "--l3", "0.45", "--json"]) == 0
    expected = json.loads(capsys.readouterr().out)
    assert job["answer"]["fb"] == pytest.approx(expected["fb"], rel=1e-9)
    steps = [(s["done"], s["total"]) for s in seen if s["total"]]
    assert all(a <= b for (a, _), (b, _) in itertools.pairwise(steps))
    assert all(done <= total for done, total in steps)
    assert job["total"] >= 12 and job["done"] == job["total"]  # the last line: every step


def test_a_job_stopped_ends_its_process_and_a_bad_kind_is_refused():
    with running() as server:
        status, job = server.post("api/job?kind=decide")
        assert status == 200 and job["state"] == "running"
        pid = job["pid"]
        assert psutil.pid_exists(pid)
        status, stopped = server.post("api/job/stop?kind=decide")
        assert status == 200 and stopped["state"] == "stopped", stopped
        assert not psutil.pid_exists(pid) or psutil.Process(pid).status() == psutil.STATUS_ZOMBIE
        status, bad = server.post("api/job?kind=dance")
        assert status == 400 and bad["field"] == "kind"


def test_the_free_coupled_search_reports_each_step_up_to_its_total():
    calls: list[tuple[int, int]] = []
    found = free_flexibility(
        HexapodDesign(), progress=lambda done, total: calls.append((done, total))
    )
    totals = {total for _, total in calls}
    assert len(totals) == 1 and calls[-1][0] == calls[-1][1]
    assert [done for done, _ in calls] == list(range(1, calls[-1][1] + 1))
    assert len(found.extremes) == 12 and calls[-1][1] >= 12


def test_a_job_whose_command_crashes_shows_one_line_saying_so():
    import subprocess
    import sys
    import tempfile

    from hexaleg.explore.jobs import Job

    crash = (  # a command's progress, then a Python error where its answer should be
        "import sys; print('hexaleg: 1/2 designs (50.0 %)', file=sys.stderr, flush=True); "
        "raise ValueError('Out of range float values are not JSON compliant: inf')"
    )
    process = subprocess.Popen(
        [sys.executable, "-c", crash], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True
    )
    job = Job("decide", process, tempfile.TemporaryDirectory())
    job.follow()
    shown = job.to_dict()
    assert shown["state"] == "failed" and (shown["done"], shown["total"]) == (1, 2)
    assert "\n" not in shown["error"] and shown["error"].startswith("hexaleg decide crashed (")
    assert "not JSON compliant" in shown["error"] and "terminal" in shown["error"]
