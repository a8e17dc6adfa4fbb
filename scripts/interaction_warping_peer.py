#!/usr/bin/env python3
"""Runs the Interaction Warping peer (ondrejbiza/shapewarping) on partreg's observation files.

Used by scripts/bench_interaction_warping.sh, which puts the peer's sources on PYTHONPATH. This file only
calls the peer's own functions; none of its code is copied here.

  infer CANONICAL.pkl TRAIN_DIR OBSERVED.ply OUT_MESH.ply OUT.json

Frames. Our ShapeNet folders are y up; the peer's planar search turns about z, so its canonical is trained
with `learn_warp --rot-x pi/2` (y -> z) and every observation is turned the same way before inference and
the result turned back after. Scale. The peer scales each training mesh to a radius of 0.1 about its
centroid and starts inference at scale 1 (its default), with Adam steps of 0.01: it expects objects of
the training size. The observation is therefore multiplied by the category's mean training factor
(0.1 / radius, over TRAIN_DIR's meshes: the truth is never used) and the result divided by it. Both maps
are rigid-plus-uniform-scale and undone exactly, so the figures are in the observation's own frame.
"""
import json
import sys
import time
from pathlib import Path

import numpy as np
import torch
import trimesh

from shapewarping.lib import object_warping, utils

UP_TO_Z = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])  # Rx(pi/2): y -> z
PEER_RADIUS = 0.1                 # learn_warp's scale_points_circle base_scale
PEER_OBSERVED_POINTS = 2000       # its ndf_interface pcd_subsample_points (farthest-point sampled)
PEER_STARTS = 12                  # its ndf_interface: warp_to_pcd_se2(n_angles=12, n_batches=1)


def training_scale(train_dir: Path) -> float:
    """The mean over training meshes of the factor learn_warp applies to each (0.1 / max centred radius)."""
    factors = []
    for path in sorted(train_dir.iterdir()):
        mesh = utils.trimesh_load_object(path)
        radius = np.max(np.linalg.norm(np.asarray(mesh.vertices) - mesh.centroid, axis=1))
        factors.append(PEER_RADIUS / radius)
    return float(np.mean(factors))


def read_points(path: Path) -> np.ndarray:
    loaded = trimesh.load(str(path))
    return np.asarray(loaded.vertices, dtype=np.float64)


def infer(canonical_path: Path, train_dir: Path, observed_path: Path, mesh_out: Path, json_out: Path):
    np.random.seed(2023)
    torch.manual_seed(2023)
    scale = training_scale(train_dir)
    observed = read_points(observed_path)
    peer_points = (scale * observed @ UP_TO_Z.T).astype(np.float32)
    if len(peer_points) > PEER_OBSERVED_POINTS:
        peer_points, _ = utils.farthest_point_sample(peer_points, PEER_OBSERVED_POINTS)

    canonical = utils.CanonObj.from_pickle(str(canonical_path))
    cpu_start, wall_start = time.process_time(), time.perf_counter()
    warping = object_warping.ObjectWarpingSE2Batch(
        canonical, peer_points, torch.device("cpu"), **object_warping.PARAM_1, init_scale=1.0)
    _, cost, parameters = object_warping.warp_to_pcd_se2(warping, n_angles=PEER_STARTS, n_batches=1)
    cpu_seconds, wall_seconds = time.process_time() - cpu_start, time.perf_counter() - wall_start

    mesh = canonical.to_transformed_mesh(parameters)
    vertices = np.asarray(mesh.vertices, dtype=np.float64) @ UP_TO_Z / scale  # back to the data frame
    trimesh.Trimesh(vertices, np.asarray(mesh.faces), process=False).export(str(mesh_out))
    json_out.write_text(json.dumps({
        "observed": str(observed_path), "observed_points": int(len(peer_points)),
        "cost": float(cost), "cpu_seconds": cpu_seconds, "wall_seconds": wall_seconds,
        "torch_threads": torch.get_num_threads(), "data_to_peer_scale": scale,
        "scale": [float(s) for s in parameters.scale],
    }, indent=1) + "\n")


def main(argv):
    if len(argv) != 7 or argv[1] != "infer":
        print("usage: interaction_warping_peer.py infer CANONICAL.pkl TRAIN_DIR OBSERVED.ply OUT_MESH.ply OUT.json",
              file=sys.stderr)
        return 2
    infer(*(Path(a) for a in argv[2:]))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
