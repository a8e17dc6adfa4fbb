"""Depth images from Python: segment_depth and register_depth agree with the rendered scene's truth, and bad
input raises partreg's errors."""
import json
import math
import os
import subprocess

import numpy as np
import pytest

MUG = "mugs/5c48d471200d2bf16e8a121e6886e18d.obj"


def _render(tmp_path, data_dir, *extra):
    executable = os.environ.get("PARTREG_EXECUTABLE")
    if not executable:
        pytest.skip("PARTREG_EXECUTABLE not set")
    mesh = data_dir / MUG
    if not mesh.exists():
        pytest.skip(f"shared data absent: {mesh}")
    out = tmp_path / "scene"
    subprocess.run([executable, "scene", str(mesh), "--out", str(out), "--quiet", *extra], check=True)
    return out


def test_segment_depth_cuts_the_rendered_mug(partreg, tmp_path, data_dir):
    scene = _render(tmp_path, data_dir, "--size", "0.12")
    truth = json.loads((scene / "scene.json").read_text())
    intrinsics = json.loads((scene / "intrinsics.json").read_text())
    cut = partreg.segment_depth(str(scene / "depth.png"), intrinsics)
    assert "nearest the image centre" in cut["choice"]
    plane = np.array(truth["table_plane"][:3])
    assert math.degrees(math.acos(min(1.0, float(np.dot(cut["up"], plane))))) < 1.0
    T = np.array(truth["objects"][0]["T_camera_object"])
    mug = np.asarray(partreg.read_mesh(str(scene / "object_0.ply")).vertices)
    centre = (mug.min(axis=0) + mug.max(axis=0)) / 2
    assert np.linalg.norm(cut["object"].mean(axis=0) - centre) < 0.06
    assert T.shape == (4, 4)


def test_depth_input_errors(partreg):
    K = {"fx": 10.0, "fy": 10.0, "cx": 3.5, "cy": 2.5, "width": 8, "height": 6}
    with pytest.raises(partreg.InputError):  # a (6, 7) image for an 8 x 6 camera
        partreg.segment_depth(np.ones((6, 7), dtype=np.float32), K)
    with pytest.raises(partreg.InputError):  # too few points to hold a table
        partreg.segment_depth(np.ones((6, 8), dtype=np.float32), K)
    with pytest.raises(ValueError):  # NaN is not JSON
        partreg.segment_depth(np.ones((6, 8), dtype=np.float32), dict(K, fx=float("nan")))
    with pytest.raises(partreg.UsageError):
        partreg.segment_depth(np.ones((6, 8), dtype=np.float32), K, pick=(100, 1))
    with pytest.raises(partreg.UsageError):
        partreg.segment_depth(np.ones((6, 8), dtype=np.float32), K, no_such_setting=1)


def test_register_depth_stands_the_mug_on_the_table(partreg, tmp_path, data_dir, cli_dir):
    # The model is in the mugs' own units (diagonal about 1): the scene is rendered in them, every length of the
    # sensor and of the cut scaled alike (a 0.12 m mug at 0.6 m, scaled by 1 / 0.12).
    s = 1 / 0.12
    scene = _render(tmp_path, data_dir, "--size", "1", "--distance", str(0.6 * s), "--spacing", str(0.2 * s),
                    "--noise", str(0.0015 / s), "--baseline", str(0.075 * s), "--edge-jump", str(0.02 * s))
    model = partreg.read_model(str(cli_dir / "mugs.prm"))
    result, cut = partreg.register_depth(model, str(scene / "depth.png"), str(scene / "intrinsics.json"),
                                         scene_voxel=0.004 * s, plane_distance=0.01 * s,
                                         cluster_tolerance=0.02 * s)
    assert cut["up_axis_degrees"] < 10.0
    truth = np.asarray(partreg.read_mesh(str(scene / "object_0.ply")).vertices)
    errors = partreg.measure_errors(result.deformed, result.part, model.part_names, truth)
    # Measured 0.096 (one rendered view, the cut drops the mug's bottom centimetre and its edge pixels); a mug
    # stood upside down or on its side is above 0.2.
    assert errors["symmetric_rms_per_diagonal"] < 0.12
    # The depth image's free space reaches the verdict; the registered mug keeps out of the space the camera saw
    # empty (measured 0; the doubtful threshold is 0.08).
    assert result.figures.free_space_violation is not None
    assert result.figures.free_space_violation < 0.08, result.figures.free_space_violation
