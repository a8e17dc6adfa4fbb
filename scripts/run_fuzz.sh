#!/usr/bin/env bash
# Builds the libFuzzer harnesses (clang-14, ASan + UBSan on all of partreg) into ./build-fuzz, fuzzes each
# for FUZZ_SECONDS (default 60) starting from its committed corpus (new inputs go to a scratch copy, not
# into the repository), as many at once as the machine has cores, then replays the whole committed corpus
# (seeds and every crash kept) once.
# A crash, a sanitizer report, an escaping exception or a hang fails the run; its input is saved under
# build-fuzz/artifacts/: add it to tests/fuzz/corpus/<harness>/ once fixed, as a regression case.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${FUZZ_SECONDS:-60}"
harnesses=(ply pcd xyz mesh gltf vtp model labels frames views csv script)
# -O1 with line tables and without NDEBUG (the empty build type: the top-level CMakeLists leaves it empty
# for PARTREG_FUZZ, so no -O3 -DNDEBUG is added): Eigen's asserts stay on, and the readers run a few times
# faster than at -O0 for a build that is not much slower.
CC=clang-14 CXX=clang++-14 cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE= -DCMAKE_CXX_FLAGS="-O1 -gline-tables-only" \
  -DPARTREG_FUZZ=ON -DPARTREG_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-fuzz --parallel "$(nproc)" --target "${harnesses[@]/#/fuzz_}"
mkdir -p build-fuzz/artifacts
# Leaks are not findings here: PCL, VTK and assimp keep static state for the process's life.
export ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1

fuzz_one() {
  local harness="$1" scratch="build-fuzz/corpus/$1"
  mkdir -p "${scratch}"
  "build-fuzz/tests/fuzz/fuzz_${harness}" "${scratch}" "tests/fuzz/corpus/${harness}" -max_total_time="${seconds}" \
    -timeout=10 -rss_limit_mb=2048 -max_len=65536 -print_final_stats=1 \
    -artifact_prefix="build-fuzz/artifacts/${harness}-" 2>"build-fuzz/fuzz_${harness}.log"
}

# A new finding of this bounded run is reported loudly but fails the run only with PARTREG_FUZZ_STRICT=1:
# a chance discovery must not block every submission. Fix it, then keep its input in the corpus, whose
# replay below always fails on a crash.
report() {
  local harness="$1" status="$2"
  if [ "${status}" != 0 ]; then
    tail -n 60 "build-fuzz/fuzz_${harness}.log" >&2
    echo "fuzz_${harness}: NEW FINDING, input in build-fuzz/artifacts/${harness}-*" >&2
    if [ "${PARTREG_FUZZ_STRICT:-0}" = 1 ]; then exit 1; fi
  fi
  echo "fuzz_${harness}: $(grep -E "stat::number_of_executed_units" "build-fuzz/fuzz_${harness}.log" | tail -n 1)" >&2
}

jobs_at_once="$(nproc)"
for ((first = 0; first < ${#harnesses[@]}; first += jobs_at_once)); do
  batch=("${harnesses[@]:first:jobs_at_once}")
  pids=()
  for harness in "${batch[@]}"; do
    echo "fuzz_${harness}: ${seconds} s" >&2
    fuzz_one "${harness}" &
    pids+=($!)
  done
  for i in "${!batch[@]}"; do
    status=0
    wait "${pids[$i]}" || status=$?
    report "${batch[$i]}" "${status}"
  done
done
(cd build-fuzz && ctest --output-on-failure --label-regex '^fuzz$' --timeout 300)
