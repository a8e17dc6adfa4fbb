#!/usr/bin/env bash
# partreg as a user gets it: `cmake --install` into a temporary prefix, then the README's "Use it from CMake"
# (find_package and pkg-config) and "Use it from Python" sections, extracted from README.md and run as
# written against that prefix, in a scratch folder that looks like the repository root after the README's
# commands (mugs.prm from the Python tests' fixture). Without ../shared/data the programs are still built
# (and the module imported), then the test exits 77 (skip).
# Usage: install_test.sh BUILD_DIR SOURCE_DIR DATA_DIR MODEL PYTHON (PYTHON "none": the module was not built)
set -euo pipefail
build_dir=$1 source_dir=$2 data_dir=$3 model=$4 python=$5
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
prefix=$scratch/prefix

echo "== cmake --install into $prefix"
cmake --install "$build_dir" --prefix "$prefix" >"$scratch/install.log"
echo "installed $(wc -l <"$build_dir/install_manifest.txt") files"
for file in include/partreg/version.hpp lib/cmake/partreg/partregConfig.cmake \
            lib/cmake/partreg/partregConfigVersion.cmake lib/pkgconfig/partreg.pc bin/partreg; do
  [ -e "$prefix/$file" ] || { echo "not installed: $file"; exit 1; }
done
"$prefix/bin/partreg" --version
bash "$source_dir/tests/install/check_public_headers.sh" "$prefix/include"

# The README's blocks of one section, by language: section_blocks "Use it from CMake" cmake > file
section_blocks() {
  awk -v section="## $1" -v language="$2" '
    /^## / { on = ($0 == section) }
    on && $0 == "```" language { block = 1; next }
    block && /^```/ { block = 0; next }
    block' "$source_dir/README.md"
}

root=$scratch/root
mkdir -p "$root/consumer" "$scratch/shared"
ln -s "$build_dir" "$root/build"
ln -s "$source_dir/assets" "$root/assets"
[ -d "$data_dir" ] && ln -s "$(realpath "$data_dir")" "$scratch/shared/data"
section_blocks "Use it from CMake" cmake >"$root/consumer/CMakeLists.txt"
section_blocks "Use it from CMake" cpp >"$root/consumer/consumer.cpp"
section_blocks "Use it from CMake" sh >"$scratch/cmake_commands.sh"
section_blocks "Use it from Python" python >"$root/mug_from_python.py"
section_blocks "Use it from Python" sh >"$scratch/python_commands.sh"
for file in consumer/CMakeLists.txt consumer/consumer.cpp mug_from_python.py; do
  [ -s "$root/$file" ] || { echo "README.md has no block for $file"; exit 1; }
done

# The prefix is a temporary one: tell CMake, pkg-config and Python where it is (README: "another prefix").
export CMAKE_PREFIX_PATH=$prefix PKG_CONFIG_PATH=$prefix/lib/pkgconfig
cd "$root"
if [ "$python" != none ]; then
  python_dir=$(find "$prefix/lib" -type d -name dist-packages | head -n 1)
  export PYTHONPATH=$python_dir
  export PATH="$(dirname "$python"):$PATH"  # python3 is the interpreter the module was built for
  echo "== import partreg from $python_dir"
  python3 -c "import partreg; print('partreg', partreg.__version__, 'from', partreg.__file__)"
fi

if [ ! -d "$data_dir/mugs" ]; then
  echo "== building the consumer only: shared data absent ($data_dir)"
  cmake -S consumer -B consumer/build >/dev/null && cmake --build consumer/build
  exit 77
fi
[ -f "$model" ] || { echo "no model $model (the python_test_data fixture did not run)"; exit 1; }
mkdir -p out && cp "$model" out/mugs.prm  # where the README's commands put it
echo "== README: Use it from CMake"
bash -euxo pipefail "$scratch/cmake_commands.sh"
if [ "$python" != none ]; then
  echo "== README: Use it from Python"
  bash -euxo pipefail "$scratch/python_commands.sh"
fi
