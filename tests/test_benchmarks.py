"""Smoke test: the benchmark entry point runs on tiny sizes and its agreement checks pass."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

RUN = Path(__file__).resolve().parent.parent / "benchmarks" / "run.py"


@pytest.mark.slow  # every workload, a minute on 2 cores
@pytest.mark.skipif(not RUN.is_file(), reason="benchmarks/ not shipped in this install")
def test_benchmarks_run_quick_and_agree():
    result = subprocess.run(
        [sys.executable, str(RUN), "--quick", "--json", "--repeats", "1"],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert result.returncode == 0, result.stderr
    rows = json.loads(result.stdout)["rows"]
    workloads = {r["workload"].split(",")[0] for r in rows}
    assert workloads >= {
        "forward kinematics",
        "Monte Carlo workspace",
        "w_A",
        "inverse kinematics",
        "optimum-w pose",
        "axis-locked FB",
        "free-coupled FB",
        "Fig 15 sweep",
        "import a hexapod URDF",
    }
    for row in rows:
        if "not installed" in row["note"]:
            continue  # an alternative from the [bench] extra
        assert row["median_s"] > 0
        if row["max_difference"] is not None:
            # exact kernels agree to round-off; iterative IK solvers to their tolerance
            limit = 1e-6 if "inverse kinematics" in row["workload"] else 1e-5
            assert row["max_difference"] <= limit
