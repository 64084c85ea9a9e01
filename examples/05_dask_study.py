"""The same study on a Dask cluster: here a 2-worker LocalCluster bound to 127.0.0.1.

On a real cluster, pass the scheduler's address instead:
    hexaleg study --scheduler tcp://SCHEDULER:8786 -o DIR
Needs the dask extra: pip install 'hexaleg[dask]'.

Run: python examples/05_dask_study.py
"""

import tempfile
from pathlib import Path

import dask
import numpy as np
from distributed import Client, LocalCluster

from hexaleg.study import StudySpec, peak_table, run_study


def main() -> None:
    """Run the example and print what it shows."""
    spec = StudySpec(l1_ratios=(0.10,), l3_ratios=tuple(np.linspace(0.2, 0.6, 9)))
    with tempfile.TemporaryDirectory(prefix="hexaleg-dask-") as scratch:
        # The study and Dask's own scratch space (dask-scratch-space, made in the temp
        # folder by default) both live in this folder, removed at the end.
        with (
            dask.config.set({"temporary-directory": scratch}),
            LocalCluster(
                n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None
            ) as cluster,
            Client(cluster) as client,
        ):
            print(f"scheduler at {cluster.scheduler_address}")
            table = run_study(spec, Path(scratch) / "study", executor=client.get_executor())
    peak = peak_table(table).iloc[0]
    print(
        f"{len(table)} designs; FB peaks at l3 ratio {peak['peak_l3_ratio']:.3f} "
        f"(FB {peak['peak_fb']:.4f})"
    )


if __name__ == "__main__":
    main()
