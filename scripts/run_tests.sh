#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: install packages, build, run ctest (the window test under
# xvfb-run included; benchmarks not), then the
# core tests once more under AddressSanitizer and UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure --label-exclude bench --parallel 2 --timeout 900)

cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPARTREG_CORE_ONLY=ON \
  -DPARTREG_SANITIZE=ON -DPARTREG_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-sanitize --parallel "$(nproc)"
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure --label-regex core --timeout 900)
