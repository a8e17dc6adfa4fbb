"""The Python module on real data: every bound function, results equal to the command line's to 1e-9 where
the CLI writes full precision (JSON), bad input raising the documented exception with the library's message.
ctest runs each test function as its own test (label python)."""
import json
import os
import subprocess
import threading
import time

import numpy as np
import pytest

from conftest import read_ascii_ply_mesh

EXACT = 1e-9  # the CLI's JSON holds every double to round-trip precision
CPD_CLOSE = EXACT  # CPD is bit-repeatable across processes (its E-step sums in a fixed order)


def test_version_matches_the_command_line(partreg):
    executable = os.environ.get("PARTREG_EXECUTABLE")
    if not executable:
        pytest.skip("PARTREG_EXECUTABLE not set")
    printed = subprocess.run([executable, "--version"], capture_output=True, text=True, check=True).stdout
    assert printed.strip() == f"partreg {partreg.__version__}"
    assert partreg.model_format_version >= 2


def test_model_accessors(partreg, model):
    assert model.category == "mugs"
    assert model.has_parts and sorted(model.part_names) == ["body", "handle"]
    assert [space.name for space in model.spaces] == ["holistic"] + model.part_names
    # 500 canonical points asked for, and more where a part needs its floor (min_part_points).
    assert model.canonical.shape[0] >= 500 and model.canonical.shape[1] == 3
    assert model.canonical.dtype == np.float64
    assert model.canonical_part.shape == (model.canonical.shape[0],)
    assert set(np.unique(model.canonical_part)) == {0, 1}
    # Normalised units: the canonical instance's bounding-box diagonal is 1 (its M points a sample of it).
    extent = model.canonical.max(axis=0) - model.canonical.min(axis=0)
    assert 0.95 < np.linalg.norm(extent) <= 1.0 + 1e-12
    data = model.to_data(np.ascontiguousarray(model.canonical))
    assert np.allclose(data, model.centre + model.scale * model.canonical, atol=EXACT)
    assert len(model.training_instances) == 10 and model.canonical_name in model.training_instances
    # The coupled seam weight training chose among its candidates on held-out mugs; register's default uses it.
    assert model.seam_weight in partreg.training_defaults()["seam_weights"]
    assert "held-out instances" in model.seam_weight_choice
    trials = model.seam_weight_trials
    assert sorted(trials) == sorted(partreg.training_defaults()["seam_weights"])
    assert all(0.0 < error < 0.2 for error in trials.values())
    assert partreg.registration_defaults()["seam_weight"] == "model"
    assert model.canonical_mesh.faces.shape[1] == 3 and model.canonical_mesh.vertices.shape[0] > 0
    # Views, not copies: two reads share memory; read-only, since every registration reads the model.
    assert np.shares_memory(model.canonical, model.canonical)
    assert not model.canonical.flags.writeable and not model.spaces[0].basis.flags.writeable
    with pytest.raises(partreg.UsageError, match="no_such_part"):
        model.space("no_such_part")


def test_shape_space_accessors(partreg, model):
    for space in model.spaces:
        m, q = space.point_count, space.dimensions
        assert space.mean.shape == (3 * m,) and space.basis.shape == (3 * m, q)
        assert space.kernel_basis.shape == (3 * m, q) and space.kernel_mean.shape == (3 * m,)
        assert np.all(np.diff(space.variances) <= 0), "variances are ordered, descending"
        assert space.training_latents.shape == (len(model.training_instances), q)
        assert 0 < space.explained_fraction().sum() <= 1 + 1e-12
        # The shape at a latent is C + G W(x) = C + kernel_mean + kernel_basis x (shape_space.hpp).
        latent = np.sqrt(space.variances) * np.linspace(-1, 1, q)
        expected = space.canonical + (space.kernel_mean + space.kernel_basis @ latent).reshape(m, 3)
        assert np.allclose(space.deformed(latent), expected, atol=1e-12)
        assert np.allclose(space.weights(latent), (space.mean + space.basis @ latent).reshape(m, 3), atol=1e-12)
        assert np.allclose(model.shape_at(latent, space.name), model.to_data(space.deformed(latent)), atol=1e-12)
        # Orthonormal directions: a wrong basis (or a copy in the wrong memory order) fails here.
        assert np.allclose(space.kernel_basis.T @ space.kernel_basis, np.eye(q), atol=1e-8)
        with pytest.raises(partreg.UsageError, match="latent"):
            space.deformed(np.zeros(q + 1))


def test_register_equals_the_command_line(partreg, registered, cli_register, cli_dir):
    assert registered.variant == cli_register["variant"] == "hol+part"
    assert [fit.space for fit in registered.fits] == [space["space"] for space in cli_register["spaces"]]
    for fit, expected in zip(registered.fits, cli_register["spaces"]):
        assert np.allclose(fit.latent, expected["latent"], rtol=0, atol=EXACT)
        assert np.allclose(fit.T_observed_canonical, expected["T_observed_canonical"], rtol=0, atol=EXACT)
        assert fit.cost == pytest.approx(expected["cost"], rel=EXACT)
        assert fit.iterations == expected["iterations"]
        assert fit.hypotheses == expected["pose_hypotheses"]
        assert fit.score == pytest.approx(expected["selection_score"], rel=EXACT)
        # None in the JSON (one start, as a hol+part part) is inf here.
        runner_up = expected["runner_up_score"]
        assert fit.runner_up_score == (np.inf if runner_up is None else pytest.approx(runner_up, rel=EXACT))
    for figure in ("mean", "p90", "mean_normalised", "p90_normalised"):
        assert getattr(registered.fit, figure) == pytest.approx(cli_register["fit"][figure], rel=EXACT)
    assert registered.fit.mean_normalised < 0.05, "a real mug fits within 5% of the diagonal"
    # The refinement (on by default) reports the same as the command line's result JSON.
    refinement, expected = registered.refinement, cli_register["refinement"]
    assert expected["enabled"] and expected["applied"] and refinement.applied
    for count in ("points", "observed", "iterations"):
        assert getattr(refinement, count) == expected[count]
    assert refinement.mean_movement == pytest.approx(expected["mean_movement_normalised"], rel=EXACT)
    assert refinement.noise == pytest.approx(expected["noise_normalised"], rel=EXACT)
    assert refinement.outlier_weight == pytest.approx(expected["outlier_weight"], rel=EXACT)
    assert refinement.width == pytest.approx(expected["kernel_width_normalised"], rel=EXACT)
    assert refinement.width >= partreg.registration_defaults()["refine_beta"], "never finer than refine_beta"
    assert refinement.max_movement == pytest.approx(expected["max_movement_normalised"], rel=EXACT)
    # Whether the space fits ended in a Gaussian mixture: not on a clean scan, the same read either way.
    mixture, expected = registered.mixture, cli_register["mixture"]
    assert not mixture.applied and not expected["applied"]
    assert mixture.noise == pytest.approx(expected["noise_normalised"], rel=EXACT)
    assert 0 < mixture.noise < partreg.registration_defaults()["mixture_noise"]
    assert mixture.sigma == expected["sigma_normalised"] == 0
    # A point moves towards observed points within the refinement's gate (0.1 of the diagonal): by about a
    # gate at most (0.105 on this mug in one run, under 0.1 in another: the parallel sums' order varies),
    # never flung.
    assert 0 < refinement.mean_movement < refinement.max_movement < 0.15, "it moves points by a gate at most"
    # The points file holds float32 coordinates: equal to float32 rounding.
    cli_points = partreg.read_cloud(cli_dir / "register_points.ply")
    assert registered.deformed.shape == cli_points.shape
    assert np.allclose(registered.deformed, cli_points, rtol=0, atol=1e-6)
    assert registered.part.shape == (registered.deformed.shape[0],)


def test_result_history_and_space_fits(partreg, registered):
    spaces = [fit.space for fit in registered.fits]
    assert spaces[0] == "holistic" and set(spaces[1:]) == {"body", "handle"}
    assert len(registered.history) >= len(spaces)
    assert {step.space for step in registered.history} == set(spaces)
    for fit in registered.fits:
        steps = [step for step in registered.history if step.space == fit.space]
        assert steps[-1].latent.shape == fit.latent.shape
        assert steps[-1].T_observed_canonical.shape == (4, 4)
        assert registered.space_fit(fit.space).cost == fit.cost
    with pytest.raises(partreg.UsageError):
        registered.space_fit("spout")
    # The deformed points are a view of the result (no copy), the caller's to write (Open3D needs that).
    assert np.shares_memory(registered.deformed, registered.deformed)
    assert not registered.deformed.flags.owndata and registered.deformed.flags.writeable


def test_deform_mesh_equals_the_command_line(partreg, model, registered, cli_dir):
    mesh = partreg.deform_mesh(model, registered)
    vertices, faces = read_ascii_ply_mesh(cli_dir / "register_mesh.ply")
    assert np.array_equal(mesh.faces, faces)
    # The CLI's PLY mesh is ascii with 9 significant digits (mug coordinates are below 1).
    assert np.allclose(mesh.vertices, vertices, rtol=0, atol=2e-9)


def test_mesh_stretch_is_the_largest_edge_ratio_as_the_command_line_prints_it(partreg, model, registered,
                                                                              cli_register):
    mesh = partreg.deform_mesh(model, registered)
    canonical = model.canonical_mesh  # normalised: the model's diagonal is 1
    edges = np.vstack([mesh.faces[:, [0, 1]], mesh.faces[:, [1, 2]], mesh.faces[:, [2, 0]]])
    before = np.linalg.norm(canonical.vertices[edges[:, 0]] - canonical.vertices[edges[:, 1]], axis=1)
    after = np.linalg.norm(mesh.vertices[edges[:, 0]] - mesh.vertices[edges[:, 1]], axis=1) / model.scale
    kept = before > 1e-9
    stretch = partreg.mesh_stretch(model, registered)
    assert stretch == pytest.approx(np.max(after[kept] / before[kept]), rel=1e-12)
    assert stretch > 1.0, "a held-out mug is not the canonical: some edge lengthens"
    assert stretch == pytest.approx(cli_register["mesh_stretch"], rel=1e-9)


def test_transfer_frames_equals_the_command_line(partreg, model, registered, cli_dir, source_dir):
    frames = partreg.read_frames(source_dir / "assets" / "frames" / "mug_handle_grasp.json")
    moved = partreg.transfer_frames(model, registered, frames)
    expected = json.loads((cli_dir / "register_frames.json").read_text())["frames"]
    assert [frame.name for frame in moved] == [frame["name"] for frame in expected]
    for frame, cli in zip(moved, expected):
        assert np.allclose(frame.position, cli["position"], rtol=0, atol=EXACT)
        assert np.allclose(frame.rotation, cli["rotation"], rtol=0, atol=EXACT)
    grasp = partreg.Frame("grasp", np.zeros(3))
    assert np.array_equal(grasp.rotation, np.eye(3))


def test_deform_points_moves_the_canonical_onto_the_result(partreg, model, observed_mug):
    # Holistic: the canonical points themselves move exactly as the registration moved them.
    result = partreg.register(model, partreg.read_cloud(observed_mug))
    canonical_in_data = model.to_data(np.ascontiguousarray(model.canonical))
    moved = partreg.deform_points(model, result, canonical_in_data)
    assert np.allclose(moved, result.deformed, rtol=0, atol=1e-9)
    assert moved.flags.writeable, "a new array: the caller's own"
    # A wrong answer would fail: the undeformed canonical is far from the result.
    assert np.abs(canonical_in_data - result.deformed).max() > 1e-3


def test_cpd_equals_the_command_line(partreg, data_dir, cli_dir):
    source = partreg.read_cloud(data_dir / "drills" / "drill_1.pcd")
    target = partreg.read_cloud(data_dir / "drills" / "drill_2.pcd")
    rigid = partreg.cpd(source, target, mode="rigid")
    cli = json.loads((cli_dir / "cpd_rigid.json").read_text())
    assert np.allclose(rigid.T_target_source, cli["T_target_source"], rtol=0, atol=CPD_CLOSE)
    assert rigid.sigma2 == pytest.approx(cli["sigma2"], rel=CPD_CLOSE)
    assert rigid.iterations == cli["iterations"] and rigid.stop_reason == cli["stop_reason"]
    nonrigid = partreg.cpd(source, target)  # mode="nonrigid", beta=2, lambda_=2 as the CLI
    cli = json.loads((cli_dir / "cpd_nonrigid.json").read_text())
    assert nonrigid.sigma2 == pytest.approx(cli["sigma2"], rel=CPD_CLOSE)
    assert nonrigid.iterations == cli["iterations"]
    assert np.allclose(nonrigid.moved, partreg.read_cloud(cli_dir / "cpd_nonrigid.ply"), rtol=0, atol=1e-6)
    assert np.allclose(nonrigid.apply(source), nonrigid.moved, atol=1e-9)
    affine = partreg.cpd(source, target, mode="affine", max_iterations=50)
    assert affine.linear.shape == (3, 3) and affine.iterations <= 50
    with pytest.raises(partreg.UsageError, match="mode must be"):
        partreg.cpd(source, target, mode="elastic")
    with pytest.raises(partreg.UsageError, match="unknown cpd setting 'betta'"):
        partreg.cpd(source, target, betta=1.0)
    with pytest.raises(partreg.UsageError, match="coarse stage needs 0"):
        partreg.cpd(source, target, coarse_points=10)


def test_read_cloud_and_mesh(partreg, data_dir, observed_mug):
    drill = partreg.read_cloud(data_dir / "drills" / "drill_1.pcd")
    assert drill.ndim == 2 and drill.shape[1] == 3 and 300 <= drill.shape[0] <= 550
    sampled = partreg.read_cloud(observed_mug, mesh_samples=1234, seed=7)
    assert sampled.shape == (1234, 3)
    assert np.array_equal(sampled, partreg.read_cloud(observed_mug, mesh_samples=1234, seed=7)), "seeded"
    mesh = partreg.read_mesh(observed_mug)
    assert mesh.faces.max() < mesh.vertices.shape[0]
    # The samples lie on the mesh: inside its bounding box.
    assert np.all(sampled >= mesh.vertices.min(axis=0) - 1e-9) and np.all(sampled <= mesh.vertices.max(axis=0) + 1e-9)


def test_views_equal_the_command_line(partreg, data_dir, cli_dir):
    mesh = partreg.read_mesh(data_dir / "mugs" / "1a97f3c83016abca21d0de04f408950f.obj")
    views = partreg.views(mesh, count=12)
    listing = json.loads((cli_dir / "views" / "views.json").read_text())["views"]
    assert len(views) == len(listing) == 12
    for view, cli in zip(views, listing):
        assert view.points.shape[0] == cli["points"]
        assert np.allclose(view.viewpoint, cli["viewpoint"], rtol=0, atol=EXACT)
        assert np.allclose(view.direction, cli["direction"], rtol=0, atol=EXACT)
        assert np.allclose(view.points, partreg.read_cloud(cli_dir / "views" / cli["file"]), rtol=0, atol=1e-6)
    directions = np.array(partreg.sphere_directions(12))
    assert np.allclose(np.linalg.norm(directions, axis=1), 1.0)
    with pytest.raises(partreg.UsageError):
        partreg.sphere_directions(13)


def test_measure_errors_known_answer(partreg):
    # Ten points 1 apart on a line; the truth is the same line moved 0.1 sideways: every closest distance is 0.1.
    deformed = np.column_stack([np.arange(10.0), np.zeros(10), np.zeros(10)])
    truth = deformed + np.array([0.0, 0.1, 0.0])
    figures = partreg.measure_errors(deformed, np.zeros(10, dtype=np.int32), ["whole"], truth, 2.0)
    assert figures["eq5"] == pytest.approx(0.01, rel=1e-12)
    assert figures["reverse_eq5"] == pytest.approx(0.01, rel=1e-12)
    assert figures["eq5_per_diagonal2"] == pytest.approx(0.01 / 4.0, rel=1e-12)
    assert figures["chamfer"] == pytest.approx(0.1, rel=1e-12)
    assert figures["chamfer_per_diagonal"] == pytest.approx(0.05, rel=1e-12)
    assert figures["symmetric_rms_per_diagonal"] == pytest.approx(0.05, rel=1e-12)
    assert figures["part_eq5_per_diagonal2"]["whole"] == pytest.approx(0.0025, rel=1e-12)
    # Without a diagonal: the truth's own bounding-box diagonal (9 along x, 0 across).
    assert partreg.measure_errors(deformed, np.zeros(10, dtype=np.int32), ["whole"], truth)["diagonal"] == pytest.approx(9.0)
    assert partreg.measure_errors(deformed, np.zeros(10, dtype=np.int32), ["whole"], deformed, 2.0)["eq5"] == 0.0


def test_measure_errors_part_against_own_part(partreg):
    # Two parts swapped end for end: the whole-truth figures are zero, each part is 5 from its own.
    truth = np.array([[0.0, 0, 0], [1, 0, 0], [3, 0, 0], [-2, 0, 0]])
    truth_part = np.array([0, 0, 1, 2], dtype=np.int32)
    turned = truth[[0, 1, 3, 2]]
    figures = partreg.measure_errors(turned, truth_part, ["body", "handle", "spout"], truth, 5.0,
                                     truth_part=truth_part)
    assert figures["symmetric_rms_per_diagonal"] == 0.0
    assert figures["own_part_rms_per_diagonal"] == pytest.approx({"body": 0.0, "handle": 1.0, "spout": 1.0})
    assert figures["own_part_rms_mean_per_diagonal"] == pytest.approx(2.0 / 3.0)
    assert "own_part_rms_per_diagonal" not in partreg.measure_errors(turned, truth_part, ["b", "h", "s"], truth)
    with pytest.raises(partreg.InputError):
        partreg.measure_errors(turned, truth_part, ["b", "h", "s"], truth, truth_part=truth_part[:2])


def test_measure_errors_equals_the_command_line(partreg, model, registered, cli_register, data_dir):
    # `register --truth` reads the true mug as 20000 surface samples with seed 2.
    truth = partreg.read_cloud(data_dir / "mugs" / "1a97f3c83016abca21d0de04f408950f.obj", mesh_samples=20000, seed=2)
    figures = partreg.measure_errors(registered.deformed, registered.part, model.part_names, truth)
    expected = cli_register["truth"]
    for name in ("diagonal", "eq5", "eq5_per_diagonal2", "reverse_eq5", "symmetric_rms_per_diagonal", "chamfer",
                 "chamfer_per_diagonal"):
        assert figures[name] == pytest.approx(expected[name], rel=EXACT), name
    for part, value in expected["part_eq5_per_diagonal2"].items():
        assert figures["part_eq5_per_diagonal2"][part] == pytest.approx(value, rel=EXACT)


def test_files_round_trip(partreg, model, registered, tmp_path):
    partreg.write_model(tmp_path / "copy.prm", model)
    copy = partreg.read_model(tmp_path / "copy.prm")
    assert np.array_equal(copy.canonical, model.canonical)
    for a, b in zip(copy.spaces, model.spaces):
        assert np.array_equal(a.basis, b.basis) and np.array_equal(a.variances, b.variances)
    partreg.write_cloud(tmp_path / "points.ply", np.ascontiguousarray(registered.deformed), part=registered.part)
    assert np.allclose(partreg.read_cloud(tmp_path / "points.ply"), registered.deformed, atol=1e-6)
    mesh = partreg.deform_mesh(model, registered)
    partreg.write_mesh(tmp_path / "mesh.ply", mesh)
    vertices, faces = read_ascii_ply_mesh(tmp_path / "mesh.ply")
    assert np.array_equal(faces, mesh.faces) and np.allclose(vertices, mesh.vertices, atol=2e-9)
    made = partreg.Mesh(np.ascontiguousarray(mesh.vertices), np.asarray(mesh.faces, dtype=np.int64))
    assert np.array_equal(made.faces, mesh.faces)
    partreg.write_frames(tmp_path / "frames.json", [partreg.Frame("a", np.array([1.0, 2.0, 3.0]))])
    assert np.array_equal(partreg.read_frames(tmp_path / "frames.json")[0].position, [1.0, 2.0, 3.0])
    with pytest.raises(partreg.UsageError, match="does not name a mesh format"):
        partreg.write_mesh(tmp_path / "mesh.stl", mesh)


def test_train_equals_the_command_line(partreg, model, data_dir, source_dir):
    trained = partreg.train(data_dir / "mugs", labels=source_dir / "assets" / "labels" /
                            "1a97f3c83016abca21d0de04f408950f.labels.json", points=500, samples=2000)
    assert trained.part_names == model.part_names and trained.canonical_name == model.canonical_name
    assert np.allclose(trained.canonical, model.canonical, rtol=0, atol=CPD_CLOSE)
    for mine, cli in zip(trained.spaces, model.spaces):  # trained through CPD: see CPD_CLOSE
        assert mine.name == cli.name
        assert np.allclose(mine.variances, cli.variances, rtol=CPD_CLOSE, atol=0)
        assert np.allclose(mine.kernel_basis, cli.kernel_basis, rtol=0, atol=CPD_CLOSE)
        assert np.allclose(mine.training_latents, cli.training_latents, rtol=0, atol=CPD_CLOSE)
    with pytest.raises(partreg.UsageError, match="seam_band"):  # the band is a normalised length
        partreg.train(data_dir / "mugs", seam_band=-0.1)


def test_train_takes_several_labels_files(partreg, data_dir, source_dir):
    # As train --labels: each file labels its own mug; --canonical picks one of them.
    folder = source_dir / "assets" / "labels"
    files = [folder / "1a97f3c83016abca21d0de04f408950f.labels.json", folder / "6aec84952a5ffcf33f60d03e1cb068dc.labels.json"]
    trained = partreg.train(data_dir / "mugs", labels=files, canonical="6aec84952a5ffcf33f60d03e1cb068dc", points=300,
                            samples=1000)
    assert trained.canonical_name == "6aec84952a5ffcf33f60d03e1cb068dc" and trained.part_names == ["body", "handle"]
    with pytest.raises(partreg.UsageError, match="none of the labelled instances"):
        partreg.train(data_dir / "mugs", labels=files, canonical="5c48d471200d2bf16e8a121e6886e18d")


def test_training_keywords_are_the_command_lines(partreg, cli_dir, data_dir):
    # The keywords come from the one table of training options: the command line's names ('-' as '_',
    # lambda_ for --lambda) and defaults, as `train --json` recorded them (points aside: the CLI asked for 500).
    defaults = partreg.training_defaults()
    options = partreg.training_options()
    assert [option["keyword"] for option in options] == list(defaults)
    assert all(option["option"] == "--" + option["keyword"].rstrip("_").replace("_", "-") for option in options)
    recorded = json.loads((cli_dir / "train.json").read_text())["settings"]
    assert sorted(option["option"][2:] for option in options) == sorted(recorded)
    assert recorded["points"] == "500"
    for option in options:
        text, value = recorded[option["option"][2:]], defaults[option["keyword"]]
        if option["keyword"] == "points":
            continue
        if isinstance(value, (int, float)):
            assert float(text) == value, option["keyword"]
        else:
            assert np.allclose([float(v) for v in text.split(",")], value), option["keyword"]
    assert "lambda_" in defaults and "seam_band" in partreg.train.__doc__
    with pytest.raises(partreg.UsageError, match="unknown training setting 'lamda'"):
        partreg.train(data_dir / "mugs", lamda=3)
    with pytest.raises(partreg.UsageError, match="up: up axis .* has zero length"):
        partreg.train(data_dir / "mugs", up=[0, 0, 0])


def test_registration_keywords_are_the_command_lines(partreg, model, observed_mug, cli_register):
    # The keywords come from the one table of registration options: the same names ('-' as '_'), the same
    # defaults as the settings the CLI recorded in its result (hol+part aside, as it was asked for).
    defaults = partreg.registration_defaults()
    options = partreg.registration_options()
    assert [option["keyword"] for option in options] == list(defaults)
    assert all(option["option"] == "--" + option["keyword"].replace("_", "-") for option in options)
    recorded = cli_register["settings"]
    assert sorted(name.replace("-", "_") for name in recorded) == sorted(defaults)
    for name, text in recorded.items():
        keyword = name.replace("-", "_")
        if keyword == "variant":
            continue
        value = defaults[keyword]
        if isinstance(value, bool):
            assert text == ("true" if value else "false"), keyword
        elif isinstance(value, (int, float)):
            assert float(text) == value, keyword
        elif value is None:
            assert text == "none", keyword
        elif isinstance(value, str):
            assert text == value, keyword
        else:
            assert np.allclose([float(v) for v in text.split(",")], value), keyword
    # A keyword reaches the registration: one outer step and no more.
    short = partreg.register(model, partreg.read_cloud(observed_mug), iterations=1)
    assert all(fit.iterations <= 1 for fit in short.fits)
    assert short.fits[0].stop_reason in ("converged", "max_iterations", "no_pairs")


# --- bad input: the documented exception, with the library's message --------------------------------------

def test_wrong_points_raise_usage_error(partreg, model):
    with pytest.raises(partreg.UsageError, match=r"points must have shape \(N, 3\), not \(100, 2\)"):
        partreg.register(model, np.zeros((100, 2)))
    with pytest.raises(partreg.UsageError, match=r"must have shape \(N, 3\), not \(100, 2\)"):
        partreg.register(model, [[0.0, 0.0]] * 100)
    with pytest.raises(partreg.UsageError, match="must be points .* not object"):
        partreg.register(model, object())
    with pytest.raises(partreg.UsageError, match="must be float64 or float32, not int64"):
        partreg.register(model, np.zeros((100, 3), dtype=np.int64))


def _point_forms(points):
    """The same points (exactly representable in float32) as every form robotics code holds them in."""
    import open3d as o3d
    points = points.astype(np.float32).astype(np.float64)
    wide = np.zeros((points.shape[0], 6))
    wide[:, ::2] = points
    cloud = o3d.geometry.PointCloud(o3d.utility.Vector3dVector(points))
    return points, {
        "float64": points,
        "float32": points.astype(np.float32),
        "float32 transposed view": np.ascontiguousarray(points.T.astype(np.float32)).T,
        "Fortran order": np.asfortranarray(points),
        "strided view": wide[:, ::2],
        "list of lists": points.tolist(),
        "Open3D Vector3dVector": o3d.utility.Vector3dVector(points),
        "Open3D PointCloud": cloud,
    }


def test_every_form_of_points_gives_the_same_points(partreg, model):
    # Model.to_data is a pure function of its points: every form must give bit-identical output.
    points, forms = _point_forms(np.random.default_rng(1).random((200, 3)) - 0.5)
    expected = model.to_data(points)
    for name, form in forms.items():
        assert np.array_equal(model.to_data(form), expected), name
    assert np.array_equal(model.to_data(points[::-1]), expected[::-1]), "negative strides"
    # A wrong conversion (a transposed copy read as rows) would fail the comparison above.
    assert not np.array_equal(model.to_data(np.ascontiguousarray(points.T).reshape(-1, 3)), expected)


def test_float32_and_open3d_register_as_float64(partreg, model, observed_mug):
    points, forms = _point_forms(partreg.read_cloud(observed_mug))
    reference = partreg.register(model, points, iterations=2, refine=False)
    for name in ("float32", "strided view", "Open3D PointCloud"):
        result = partreg.register(model, forms[name], iterations=2, refine=False)
        assert np.allclose(result.deformed, reference.deformed, rtol=0, atol=1e-9), name
    assert reference.fit.mean_normalised < 0.1


def test_an_unpickled_array_is_taken_and_a_byte_swapped_one_refused(partreg, model, observed_mug):
    import pickle
    points = partreg.read_cloud(observed_mug)
    unpickled = pickle.loads(pickle.dumps(points))  # float64, but another dtype object
    assert partreg.register(model, unpickled, iterations=1).deformed.shape == model.canonical.shape
    with pytest.raises(partreg.UsageError, match="must be float64 or float32, not >f8"):
        partreg.register(model, points.astype(">f8"))


def test_every_type_prints_what_it_holds(partreg, model, registered):
    rng = np.random.default_rng(3)
    source = rng.random((300, 3)) * [1.0, 0.3, 0.1]  # a slab: no symmetry under the turn below
    turn = np.radians(30.0)
    target = source @ np.array([[np.cos(turn), -np.sin(turn), 0], [np.sin(turn), np.cos(turn), 0], [0, 0, 1]]).T
    rigid = partreg.cpd(source, target, mode="rigid")
    angle = np.degrees(np.arccos((np.trace(rigid.rotation) - 1) / 2))
    assert angle == pytest.approx(30.0, abs=0.5)
    printed = {
        "Model": (model, "mugs"),
        "ShapeSpace": (model.spaces[0], "holistic"),
        "Mesh": (model.canonical_mesh, "vertices"),
        "Frame": (partreg.Frame("grasp", np.array([1.0, 2.0, 3.0])), "grasp at [1, 2, 3]"),
        "RegistrationResult": (registered, f"hol+part: {registered.deformed.shape[0]} points"),
        "TrustFigures": (registered.figures, f"inliers {100 * registered.figures.inlier_share:.3g}%"),
        "FitStatistics": (registered.fit, f"{100 * registered.fit.mean_normalised:.3g}% of the diagonal"),
        "SpaceFit": (registered.fits[0], f"holistic: latent [{registered.fits[0].latent[0]:.4g}"),
        "HistoryStep": (registered.history[0], "cost"),
        "Refinement": (registered.refinement, f"{registered.refinement.points} points"),
        "MixtureFinish": (registered.mixture, "not applied"),
        "RigidCpdResult": (rigid, f"rotation {angle:.4g} deg"),
        "AffineCpdResult": (partreg.cpd(source, target, mode="affine"), "300 points"),
        "NonrigidCpdResult": (partreg.cpd(source, target, max_iterations=5), "5 iterations"),
        "View": (partreg.views(source, count=12)[0], "points from ["),
        "Gripper": (partreg.Gripper(0.35, relative_to_diagonal=True), "aperture 0.35, pad"),
        "Grasp": (partreg.Grasp("pinch", [1.0, 2.0, 3.0], np.eye(3), 0.05, part="handle"),
                  "pinch on handle at [1, 2, 3], width 0.05"),
    }
    classes = {name for name in dir(partreg) if isinstance(getattr(partreg, name), type)
               and not issubclass(getattr(partreg, name), Exception)}
    assert classes == set(printed), "every class of the module is printed here"
    for name, (value, expected) in printed.items():
        text = repr(value)
        assert text.startswith(f"<partreg.{name} ") and "object at 0x" not in text, text
        assert expected in text, f"{name}: {text}"


def test_nan_points_raise_input_error(partreg, model, observed_mug):
    points = partreg.read_cloud(observed_mug)
    points[5, 1] = np.nan
    with pytest.raises(partreg.InputError, match="NaN"):
        partreg.register(model, points)


def test_missing_file_raises_input_error(partreg, tmp_path):
    missing = tmp_path / "missing.prm"
    with pytest.raises(partreg.InputError, match="missing.prm"):
        partreg.read_model(missing)
    with pytest.raises(partreg.InputError, match="missing.ply"):
        partreg.read_cloud(tmp_path / "missing.ply")
    with pytest.raises(partreg.InputError, match="missing.obj"):
        partreg.read_mesh(tmp_path / "missing.obj")


def test_model_of_another_format_version_raises_input_error(partreg, cli_dir, tmp_path):
    data = (cli_dir / "mugs.prm").read_bytes()
    version = f'"format_version":{partreg.model_format_version}'.encode()
    assert data.count(version) == 1
    other = tmp_path / "other_version.prm"
    other.write_bytes(data.replace(version, f'"format_version":{partreg.model_format_version + 1}'.encode()))
    with pytest.raises(partreg.InputError, match=f"has format version {partreg.model_format_version + 1}"):
        partreg.read_model(other)


def test_one_thread_and_two_give_the_same_bits(partreg, model, observed_mug):
    cloud = partreg.read_cloud(observed_mug)
    one, two = (partreg.register(model, cloud, threads=threads) for threads in (1, 2))
    assert np.array_equal(one.deformed, two.deformed)
    assert len(one.fits) == len(two.fits) > 0
    for first, second in zip(one.fits, two.fits):
        assert np.array_equal(first.T_observed_canonical, second.T_observed_canonical)
        assert np.array_equal(first.latent, second.latent)


def test_unknown_setting_raises_usage_error(partreg, model, observed_mug):
    with pytest.raises(partreg.UsageError, match="no_such_setting"):
        partreg.register(model, partreg.read_cloud(observed_mug), no_such_setting=1)
    with pytest.raises(partreg.UsageError, match="unknown variant 'elastic'"):
        partreg.register(model, partreg.read_cloud(observed_mug), variant="elastic")
    with pytest.raises(partreg.UsageError, match="threads must be 0"):
        partreg.register(model, partreg.read_cloud(observed_mug), threads=-1)
    with pytest.raises(partreg.UsageError, match="restarts must be in"):
        partreg.register(model, partreg.read_cloud(observed_mug), restarts=0)


def test_registration_releases_the_interpreter_lock(partreg, model, observed_mug):
    # An order of events, not a speed ratio (that is tests/bench/python_benchmark.py): this thread asks to run
    # again 20 ms after another thread entered register(). If register() held the lock through its C++ call,
    # this thread could only run after the call returned, i.e. at least result.seconds after the start.
    points = partreg.read_cloud(observed_mug)
    started, outcome = threading.Event(), {}

    def register():
        outcome["start"] = time.monotonic()
        started.set()
        # Many starting poses: a call long enough (about 0.3 s or more) that 20 ms is well inside it.
        outcome["result"] = partreg.register(model, points, variant="hol+part", restarts=32)

    worker = threading.Thread(target=register)
    worker.start()
    started.wait()
    time.sleep(0.02)
    resumed = time.monotonic() - outcome["start"]
    worker.join()
    seconds = outcome["result"].seconds
    assert seconds > 0.1, "the registration is long enough for the check to mean something"
    assert resumed < 0.5 * seconds, f"this thread ran again only after {resumed:.3f} s of a {seconds:.3f} s call"


def _stub_members(node, stubbed):
    """The public names a stub class declares (methods, properties, attributes), its stub bases' included."""
    import ast
    names = set()
    for base in node.bases:
        if isinstance(base, ast.Name) and base.id in stubbed:
            names |= _stub_members(stubbed[base.id], stubbed)
    for item in node.body:
        if isinstance(item, (ast.FunctionDef, ast.AnnAssign)):
            name = item.name if isinstance(item, ast.FunctionDef) else item.target.id
            if not name.startswith("_") or name == "__init__":
                names.add(name)
    return names


def _stub_parameters(function):
    import ast
    arguments = function.args
    positional = arguments.posonlyargs + arguments.args
    defaults = [None] * (len(positional) - len(arguments.defaults)) + list(arguments.defaults)
    named = [(a.arg, ast.unparse(d) if d is not None else None) for a, d in zip(positional, defaults)]
    named += [(a.arg, ast.unparse(d) if d is not None else None)
              for a, d in zip(arguments.kwonlyargs, arguments.kw_defaults)]
    return named + ([("**", None)] if arguments.kwarg else [])


def _compiled_parameters(member, name):
    """A pybind11 function's parameters, from the signature on the first line of its docstring."""
    import ast
    signature = member.__doc__.splitlines()[0].split(" -> ")[0]
    signature = signature[signature.index("("):]
    return _stub_parameters(ast.parse(f"def f{signature}: pass").body[0])


def _same_parameters(stub_node, member, name):
    theirs, mine = _stub_parameters(stub_node), _compiled_parameters(member, name)
    assert [n for n, _ in theirs] == [n for n, _ in mine], f"{name}: parameters differ: {theirs} against {mine}"
    import ast
    for (parameter, stub_default), (_, module_default) in zip(theirs, mine):
        if module_default is not None and stub_default is not None:
            assert ast.literal_eval(stub_default) == ast.literal_eval(module_default), f"{name}({parameter})"


def test_type_stub_matches_the_module(partreg):
    # The stub names every public function and class of the module and nothing else; every class's methods,
    # properties and attributes, and nothing else; with the module's own parameter names and defaults
    # (pybind11 writes each function's signature as the first line of its docstring).
    import ast
    import pathlib
    stub = ast.parse((pathlib.Path(partreg.__file__).parent / "__init__.pyi").read_text())
    stubbed = {node.name: node for node in stub.body if isinstance(node, (ast.FunctionDef, ast.ClassDef))}
    public = {name for name in dir(partreg) if not name.startswith("_") and name != "model_format_version"}
    public_stubbed = {name for name in stubbed if not name.startswith("_")}
    assert sorted(public - public_stubbed) == [], "public names missing from __init__.pyi"
    assert sorted(public_stubbed - public) == [], "names in __init__.pyi that the module does not have"

    for name in sorted(public):
        node, member = stubbed[name], getattr(partreg, name)
        if isinstance(node, ast.FunctionDef):
            _same_parameters(node, member, name)
            continue
        if issubclass(member, Exception):
            continue
        # A class bound with a constructor has pybind11's __init__ (its signature first in its docstring).
        declared = {key for key in vars(member) if not key.startswith("_")}
        if (member.__init__.__doc__ or "").startswith("__init__("):
            declared.add("__init__")
        members = _stub_members(node, stubbed)
        assert sorted(declared - members) == [], f"{name}: members missing from __init__.pyi"
        assert sorted(members - declared) == [], f"{name}: members in __init__.pyi that the module does not have"
        for item in node.body:
            if isinstance(item, ast.FunctionDef) and not any(
                    isinstance(d, ast.Name) and d.id == "property" for d in item.decorator_list):
                _same_parameters(item, getattr(member, item.name), f"{name}.{item.name}")


def test_the_verdict_and_its_figures_equal_the_command_lines(partreg, registered, cli_register):
    assessment = cli_register["assessment"]
    assert registered.verdict == assessment["verdict"]
    assert registered.reasons == assessment["reasons"]
    figures = assessment["figures"]
    assert registered.figures.inlier_share == pytest.approx(figures["inlier_share"], rel=1e-9)
    assert registered.figures.observed_rms == pytest.approx(figures["observed_rms_normalised"], rel=1e-9, abs=1e-12)
    assert registered.figures.latent_distance == pytest.approx(figures["latent_distance"], rel=1e-9)
    assert 0.0 < registered.figures.inlier_share <= 1.0
    assert registered.figures.free_space_violation is None  # no depth image
    assert registered.fits[0].latent_distance == pytest.approx(cli_register["spaces"][0]["latent_distance"], rel=1e-9)
