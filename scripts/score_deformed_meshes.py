#!/usr/bin/env python3
"""Scores deformed meshes against a true instance with partreg's own error code, all sampled alike.

  score_deformed_meshes.py TRUTH_MESH DEFORMED_MESH_OR_CLOUD...

Used by scripts/bench_interaction_warping.sh so that partreg's result and a peer's are measured the same
way: the truth is sampled as `partreg register --truth` samples it (20000 points, seed 2), every deformed
mesh is sampled area-uniformly to the same count (4000 points, seed 1: equal point density whatever the
method's own point count), and `partreg.measure_errors` (core/geometry/truth_errors.hpp) gives the figures, D
being the truth's diagonal. A cloud is scored as it is (no resampling). Prints one JSON object per input line.
Needs the partreg Python module on PYTHONPATH (build/python).
"""
import json
import sys

import numpy as np
import partreg

TRUTH_SAMPLES, TRUTH_SEED = 20000, 2      # as register --truth (app/partreg/commands/register_command.cpp)
DEFORMED_SAMPLES, DEFORMED_SEED = 4000, 1


def main(argv):
    if len(argv) < 3:
        print("usage: score_deformed_meshes.py TRUTH_MESH DEFORMED...", file=sys.stderr)
        return 2
    truth = partreg.read_cloud(argv[1], mesh_samples=TRUTH_SAMPLES, seed=TRUTH_SEED)
    for path in argv[2:]:
        points = partreg.read_cloud(path, mesh_samples=DEFORMED_SAMPLES, seed=DEFORMED_SEED)
        errors = partreg.measure_errors(points, np.zeros(len(points), dtype=np.int32), ["object"], truth)
        print(json.dumps({"file": path, "points": len(points),
                          "symmetric_rms_per_diagonal": errors["symmetric_rms_per_diagonal"],
                          "eq5_per_diagonal2": errors["eq5_per_diagonal2"],
                          "chamfer_per_diagonal": errors["chamfer_per_diagonal"]}))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
