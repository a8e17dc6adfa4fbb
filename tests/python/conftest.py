"""Fixtures of the Python tests: the module, the shared real data and what the command line made of it.

ctest runs each test function in its own pytest process, after the fixture test `python_test_data` has run
make_test_data.sh (PARTREG_TEST_DATA holds its outputs). Tests skip with a message naming what is absent.
"""
import json
import os
import pathlib

import numpy as np
import pytest


@pytest.fixture(scope="session")
def partreg():
    import partreg as module  # imported here so that collection does not need the built module
    return module


def _folder(variable):
    value = os.environ.get(variable)
    if not value or not pathlib.Path(value).is_dir():
        pytest.skip(f"{variable} is not a folder ({value!r}): shared data or the CLI's test data absent")
    return pathlib.Path(value)


@pytest.fixture(scope="session")
def data_dir():
    """../shared/data (PARTREG_DATA_DIR)."""
    return _folder("PARTREG_DATA_DIR")


@pytest.fixture(scope="session")
def cli_dir():
    """The command line's outputs on the shared data (make_test_data.sh)."""
    folder = _folder("PARTREG_TEST_DATA")
    if not (folder / "mugs.prm").exists():
        pytest.skip(f"{folder} holds no mugs.prm: make_test_data.sh skipped (shared data absent)")
    return folder


@pytest.fixture(scope="session")
def source_dir():
    return pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def observed_mug(data_dir):
    return data_dir / "mugs" / "5c48d471200d2bf16e8a121e6886e18d.obj"


@pytest.fixture(scope="session")
def model(partreg, cli_dir):
    return partreg.read_model(cli_dir / "mugs.prm")


@pytest.fixture(scope="session")
def cli_register(cli_dir):
    return json.loads((cli_dir / "register.json").read_text())


@pytest.fixture(scope="session")
def registered(partreg, model, observed_mug):
    """The Python side of the CLI's `register --variant hol+part` on the same mug (same sampling)."""
    points = partreg.read_cloud(observed_mug, mesh_samples=3000, seed=1)
    return partreg.register(model, points, variant="hol+part")


def read_ascii_ply_mesh(path):
    """Vertices (double) and faces of an ascii PLY mesh as partreg writes it (exact: no library in between)."""
    lines = pathlib.Path(path).read_text().splitlines()
    end = lines.index("end_header")
    vertex_count = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
    rows = [l.split() for l in lines[end + 1:end + 1 + vertex_count]]
    vertices = np.array([[float(v) for v in row[:3]] for row in rows])
    faces = np.array([[int(v) for v in l.split()[1:4]] for l in lines[end + 1 + vertex_count:]])
    return vertices, faces
