# Grasps from Python (docs/grasps.md): the same gripper test, sampling, files and transfer as the library.
import json

import numpy as np


def box(hx, hy, hz):
    corners = np.array([[x, y, z] for z in (-hz, hz) for y in (-hy, hy) for x in (-hx, hx)], dtype=np.float64)
    faces = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4], [2, 6, 3], [3, 6, 7],
                      [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]], dtype=np.int32)
    return corners, faces


def test_sampled_grasps_hold_and_a_turned_one_slips(partreg):
    vertices, faces = box(0.02, 0.03, 0.04)
    gripper = partreg.Gripper(0.1, pad_size=0.01, finger_depth=0.03)
    grasps = partreg.sample_grasps(vertices, faces, gripper, count=12, seed=3)
    assert len(grasps) >= 6
    checks = partreg.check_grasps(vertices, faces, grasps, gripper)
    assert all(check["holds"] for check in checks), [check["reason"] for check in checks]
    assert [g.quality for g in grasps] == sorted((g.quality for g in grasps), reverse=True)
    # Turned 45 degrees about its approach, the same grasp meets the faces outside the friction cone.
    g = grasps[0]
    z = g.rotation[:, 2]
    turn = np.cos(np.pi / 4) * np.eye(3) + np.sin(np.pi / 4) * np.cross(np.eye(3), z) \
        + (1 - np.cos(np.pi / 4)) * np.outer(z, z)
    turned = partreg.Grasp("turned", g.position, turn @ g.rotation, g.width)
    assert not partreg.check_grasps(vertices, faces, [turned], gripper)[0]["holds"]
    assert "partreg.Grasp" in repr(g) and "partreg.Gripper" in repr(gripper)


def test_grasps_round_trip_through_a_file(partreg, tmp_path):
    vertices, faces = box(0.02, 0.03, 0.04)
    gripper = partreg.Gripper(0.1, pad_size=0.01, finger_depth=0.03)
    grasps = partreg.sample_grasps(vertices, faces, gripper, count=5, seed=1)
    partreg.write_grasps(tmp_path / "g.json", grasps, gripper)
    back, back_gripper = partreg.read_grasps(tmp_path / "g.json")
    assert json.loads((tmp_path / "g.json").read_text())["format"] == "partreg-grasps"
    assert back_gripper.max_aperture == gripper.max_aperture
    for a, b in zip(grasps, back):
        assert a.name == b.name and np.allclose(a.position, b.position) and np.allclose(a.rotation, b.rotation)


def test_transfer_grasps_follow_the_registered_mug(partreg, model, registered):
    gripper = partreg.Gripper(0.35, pad_size=0.04, finger_depth=0.1, relative_to_diagonal=True)
    mesh = model.canonical_mesh  # normalised: data = centre + scale * normalised
    vertices = mesh.vertices * model.scale + model.centre
    grasps = partreg.sample_grasps(vertices, mesh.faces, gripper, count=10, seed=2)
    carried = partreg.transfer_grasps(model, registered, grasps, gripper)
    assert len(carried) == len(grasps)
    assert [g.quality for g in carried] == sorted((g.quality for g in carried), reverse=True)
    assert sum(g.quality > 0 for g in carried) >= len(carried) // 2
