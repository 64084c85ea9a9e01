"""Workloads on body flexibility: one design, the Fig 15 sweep (local pool and Dask), free mode."""

from __future__ import annotations

import tempfile
import time
import warnings
from concurrent.futures import ProcessPoolExecutor

import numpy as np
from alternatives import optional, step_and_bisect_extremes
from harness import Row, check_agree, median_time, missing

from hexaleg import HexapodDesign, HexapodModel
from hexaleg.design import l3_ratio_grid
from hexaleg.paper import L1_RATIOS
from hexaleg.stance import (
    StanceGeometry,
    axis_locked_extremes,
    axis_locked_flexibility,
    free_flexibility,
)
from hexaleg.statics.loads import loads_at_extremes
from hexaleg.study import StudySpec, run_study


def bench_flexibility(l3_points: int, repeats: int) -> list[Row]:
    """Axis-locked FB of one design, the Fig 15 sweep, and free-coupled FB."""
    design = HexapodDesign()
    model = HexapodModel(design)
    geometry = StanceGeometry.from_model(model, "all")

    def hexaleg_one():
        return np.array([e.value for e in axis_locked_extremes(geometry)])

    reference = hexaleg_one()
    d_one = check_agree(
        "axis-locked / step-and-bisect", reference, step_and_bisect_extremes(geometry), 1e-9
    )
    t_one = median_time(hexaleg_one, repeats)
    t_naive_one = median_time(lambda: step_and_bisect_extremes(geometry), 3, min_time=0.0)
    rows = [
        Row(
            "axis-locked FB, one design",
            "hexaleg axis_locked_extremes",
            t_one,
            None,
            None,
            "≤ 5 ms",
        ),
        Row(
            "axis-locked FB, one design",
            "step (1 mm / 1 mrad) and bisect",
            t_naive_one,
            t_naive_one / t_one,
            d_one,
        ),
    ]

    spec = StudySpec(tuple(L1_RATIOS), tuple(l3_ratio_grid(l3_points)), gait=False)
    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()  # start the workers before timing, as a long-lived pool would be

        def sweep():
            with tempfile.TemporaryDirectory() as out:
                return run_study(spec, out, executor=pool)["fb"].to_numpy()

        fb_sweep = sweep()
        t_sweep = median_time(sweep, max(3, repeats // 2), min_time=0.0)
    subset = spec.keys()[:: max(1, len(spec.keys()) // 8)]
    template = geometry

    def naive_sweep():
        out = []
        for r1, r3 in subset:
            g = template.with_design(HexapodDesign.from_ratios(r1, r3))
            out.append(step_and_bisect_extremes(g))
        return out

    t_naive_sweep = median_time(naive_sweep, 1, min_time=0.0) * len(spec.keys()) / len(subset)
    name = f"Fig 15 sweep, {len(spec.keys())} designs"
    rows += [
        Row(
            name,
            "hexaleg run_study (with statics), 2 processes",
            t_sweep,
            None,
            None,
            "≤ 2 s",
            extra={"designs": len(fb_sweep)},
        ),
        Row(
            name,
            "step and bisect, 1 process",
            t_naive_sweep,
            t_naive_sweep / t_sweep,
            None,
            note=f"timed on {len(subset)} designs, scaled",
        ),
    ]

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        free = free_flexibility(design, "all", model)
        t_free = median_time(lambda: free_flexibility(design, "all", model), 3, min_time=0.0)
    rows.append(
        Row(
            "free-coupled FB, one design",
            "hexaleg free_flexibility (multi-start SLSQP)",
            t_free,
            None,
            None,
            "≤ 0.5 s",
            note=f"FB {free.fb:.4f}, {free.iterations} iterations (climbs, SLSQP), "
            f"converged {free.converged}",
        )
    )
    locked = axis_locked_flexibility(design, "all", model)
    t_statics = median_time(lambda: loads_at_extremes(model, locked), repeats)
    rows.append(
        Row(
            "statics at nominal + 12 extremes, one design",
            "hexaleg loads_at_extremes (min-norm)",
            t_statics,
            None,
            None,
            "≤ 5 ms",
            note="13 poses: forces, torques, margin; slopes; payload capacity",
        )
    )
    short_body = HexapodDesign(body_length=0.1, body_width=0.4)  # its legs collide under yaw
    short_model = HexapodModel(short_body)
    t_collide = median_time(
        lambda: axis_locked_flexibility(short_body, "all", short_model, collisions=True),
        max(3, repeats // 2),
        min_time=0.0,
    )
    rows.append(
        Row(
            "axis-locked FB with self-collision, one design",
            "hexaleg axis_locked_flexibility(collisions=True)",
            t_collide,
            None,
            None,
            "≤ 50 ms",
            note="body 0.1 × 0.4 m, whose adjacent legs collide under yaw",
        )
    )
    free_spec = StudySpec(tuple(L1_RATIOS), tuple(l3_ratio_grid(l3_points)), mode="free")
    with ProcessPoolExecutor(2) as pool, tempfile.TemporaryDirectory() as out:
        pool.submit(int).result()
        start = time.perf_counter()
        run_study(free_spec, out, executor=pool, progress=False)
        t_free_sweep = time.perf_counter() - start
    rows.append(
        Row(
            f"free-coupled Fig 15 sweep, {len(free_spec.keys())} designs",
            "hexaleg run_study(mode='free'), 2 processes",
            t_free_sweep,
            None,
            None,
            "≤ 60 s for 320 designs",
            note="timed once",
        )
    )
    return rows


def bench_dask(l3_points: int, repeats: int) -> list[Row]:
    """The Fig 15 sweep on a 2-worker Dask LocalCluster vs the local process pool."""
    name = f"Fig 15 sweep, {4 * l3_points} designs, 2 workers"
    distributed = optional("distributed")
    if distributed is None:
        return [missing(name, "Dask LocalCluster")]
    spec = StudySpec(tuple(L1_RATIOS), tuple(l3_ratio_grid(l3_points)))

    def sweep(executor):
        with tempfile.TemporaryDirectory() as out:
            return run_study(spec, out, executor=executor, progress=False)["fb"].to_numpy()

    with ProcessPoolExecutor(2) as pool:
        pool.submit(int).result()
        reference = sweep(pool)
        t_pool = median_time(lambda: sweep(pool), max(3, repeats // 2), min_time=0.0)
    with (
        distributed.LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            host="127.0.0.1",
            dashboard_address=None,
            processes=True,
        ) as cluster,
        distributed.Client(cluster) as client,
    ):
        executor = client.get_executor()
        d = check_agree("dask / pool", reference, sweep(executor), 0.0)
        t_dask = median_time(lambda: sweep(executor), max(3, repeats // 2), min_time=0.0)
    return [
        Row(name, "local process pool", t_pool, None, None),
        Row(
            name,
            "Dask LocalCluster (127.0.0.1)",
            t_dask,
            t_dask / t_pool,
            d,
            note="ratio here: Dask time / pool time (overhead)",
        ),
    ]
