"""A small design study on a local process pool: FB against the tibia ratio (Fig 15).

Run: python examples/04_design_study.py [OUTPUT_DIR]

The table and figures are kept in OUTPUT_DIR; without it they are written to a
temporary folder, removed when the script ends.
"""

import sys
import tempfile

import numpy as np

from hexaleg.output.figures import write_study_figures
from hexaleg.study import StudySpec, peak_table, run_study


def main(out_dir: str) -> None:
    """Run the example and print what it shows."""
    spec = StudySpec(l1_ratios=(0.10, 0.20), l3_ratios=tuple(np.linspace(0.2, 0.6, 17)))
    table = run_study(spec, out_dir, workers=2)
    print(f"{len(table)} designs written to {out_dir}/study.csv")
    for peak in peak_table(table).to_dict(orient="records"):
        print(
            f"  l1 ratio {peak['l1_ratio']:.2f}: FB peaks at l3 ratio "
            f"{peak['peak_l3_ratio']:.3f} (FB {peak['peak_fb']:.4f})"
        )
    for path in write_study_figures(table, out_dir):
        print(f"  figure: {path}")


if __name__ == "__main__":
    if len(sys.argv) > 1:
        main(sys.argv[1])
    else:
        with tempfile.TemporaryDirectory(prefix="hexaleg-study-") as folder:
            main(folder)
        print(f"{folder} removed: pass OUTPUT_DIR to keep the table and figures")
