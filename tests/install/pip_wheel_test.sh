#!/usr/bin/env bash
# `pip install .` as the README gives it, offline: a wheel built by pip (setup.py runs the project's CMake) from
# a copy of what the build reads, installed into a fresh venv, imported from there and used on small arrays.
# The wheel reuses BUILD_DIR's compiled module (PARTREG_BUILD_DIR), so the test takes seconds, not a build.
# Usage: pip_wheel_test.sh BUILD_DIR SOURCE_DIR PYTHON
set -euo pipefail
build_dir=$1 source_dir=$2 python=$3
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT

# What setup.py and pyproject.toml read: nothing is written into the source tree.
mkdir -p "$scratch/src/python"
cp "$source_dir"/{pyproject.toml,setup.py,README.md,CMakeLists.txt} "$scratch/src/"
cp -r "$source_dir/python/partreg" "$scratch/src/python/"

echo "== a fresh venv (system site packages: Debian's numpy and setuptools, no network)"
"$python" -m venv --system-site-packages "$scratch/venv"
venv_python=$scratch/venv/bin/python
echo "== pip wheel --no-build-isolation"
PARTREG_BUILD_DIR=$build_dir "$venv_python" -m pip wheel --no-build-isolation --no-deps --no-index \
  -w "$scratch/wheels" "$scratch/src" >"$scratch/wheel.log" 2>&1 || { cat "$scratch/wheel.log"; exit 1; }
wheel=$(ls "$scratch"/wheels/partreg-*.whl)
echo "built $(basename "$wheel")"
unzip -l "$wheel" | grep -E "partreg/(_partreg.*\.so|__init__\.pyi?|py\.typed)$"
echo "== pip install into the venv"
"$venv_python" -m pip install --no-index --no-deps "$wheel" >"$scratch/install.log" 2>&1 ||
  { cat "$scratch/install.log"; exit 1; }

cd "$scratch"  # away from any source tree
"$venv_python" - "$scratch/venv" <<'PY'
import pathlib
import sys

import numpy as np

import partreg

where = pathlib.Path(partreg.__file__).resolve()
assert pathlib.Path(sys.argv[1]).resolve() in where.parents, f"imported {where}, not the venv's"
stub = where.parent / "__init__.pyi"
assert stub.exists() and (where.parent / "py.typed").exists(), "type stubs installed"
rng = np.random.default_rng(1)
source = (rng.random((200, 3)) * [1.0, 0.4, 0.2]).astype(np.float32)
result = partreg.cpd(source, source + np.float32(0.05), mode="rigid")
assert np.allclose(result.translation, 0.05, atol=1e-3), result
print(f"partreg {partreg.__version__} from {where.parent}: {result!r}")
PY
