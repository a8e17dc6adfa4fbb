#!/usr/bin/env bash
# The whole test suite on a fresh Debian 12 machine: install packages, build, run ctest (the window test under
# xvfb-run included; benchmarks not), then the core, io and eval tests once more under AddressSanitizer and
# UndefinedBehaviorSanitizer, then every libFuzzer harness for a bounded time and the whole fuzz regression
# corpus (scripts/run_fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
(cd build && ctest --output-on-failure --label-exclude bench --parallel 2 --timeout 900)

cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPARTREG_SANITIZE=ON \
  -DPARTREG_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-sanitize --target partreg_sanitizer_suite --parallel "$(nproc)"
(cd build-sanitize && ASAN_OPTIONS=detect_leaks=1 LSAN_OPTIONS="suppressions=$PWD/../scripts/lsan.supp" \
  ctest --output-on-failure --label-regex '^(core|io|eval)$' --label-exclude '^data$' --parallel 2 --timeout 900)

bash scripts/run_fuzz.sh
