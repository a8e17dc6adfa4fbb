#!/usr/bin/env bash
# Every table of docs/results.md, docs/results-synthetic.md and docs/benchmarks.md, regenerated: runs the evaluations (`partreg eval`,
# `partreg report`) and benchmarks behind each generated block and rewrites the block in place, stamped with
# the commit of the build's sources, the date, the machine and the commands (scripts/results_tables.py).
#
#   scripts/reproduce_results.sh [--quick] [--only ID,ID...] [--build DIR] [--docs DIR] [--work DIR]
#                                [--data DIR] [--threads N]
#
# --quick       only the quick blocks (seconds to a minute: what CI runs, into a copy of the docs)
# --only        only these blocks (ids as in the pages' <!-- BEGIN GENERATED id --> markers)
# --build       the build to run (default ./build); its sources' commit goes into the stamps
# --docs        the folder holding those pages, to rewrite (default ./docs)
# --work        where the runs are written (default a new temporary folder, removed at the end)
# --data        the shared object data (default: the build's PARTREG_DATA_DIR); blocks needing it are
#               skipped with a message when it is absent
# --threads     threads per evaluation (default 0: all cores)
# Wall time of the full set: docs/results.md ("Regenerating").
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=$root/build docs=$root/docs work="" data="" threads=0 quick=0 only=""
usage() { echo "reproduce_results: $1 (see the header of scripts/reproduce_results.sh)" >&2; exit 2; }
while [ $# -gt 0 ]; do
  case $1 in
    --quick) quick=1 ;;
    --only) only=${2:?}; shift ;;
    --build) build=$(cd "${2:?}" && pwd); shift ;;
    --docs) docs=$(cd "${2:?}" && pwd); shift ;;
    --work) work=${2:?}; shift ;;
    --data) data=${2:?}; shift ;;
    --threads) threads=${2:?}; shift ;;
    *) usage "unknown argument '$1'" ;;
  esac
  shift
done
[ -x "$build/partreg" ] || usage "no partreg in $build (build first: scripts/build.sh)"
pages=(results.md results-synthetic.md benchmarks.md)  # every page holding generated blocks
for page in "${pages[@]}"; do [ -f "$docs/$page" ] || usage "no $docs/$page"; done
if [ -z "$data" ]; then
  data=$(sed -n 's/^PARTREG_DATA_DIR:PATH=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
  data=${data:-$root/../shared/data}
fi
if [ -z "$work" ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"
work=$(cd "$work" && pwd)
# The stamp names the commit of the sources the build was made from.
source_dir=$(sed -n 's/^CMAKE_HOME_DIRECTORY:INTERNAL=//p' "$build/CMakeCache.txt" 2>/dev/null || true)
export PARTREG_STAMP_SOURCE=${source_dir:-$root}
tables="/usr/bin/python3 $root/scripts/results_tables.py"
partreg=$build/partreg bench=$build/tests/bench

commands="" block_start=0
# run COMMAND...: run it and note it for the block's stamp, the build, work and data folders named as such.
run() {
  local shown="" word
  for word in "$@"; do [[ $word == *" "* ]] && shown+="'$word' " || shown+="$word "; done
  shown=${shown% }
  shown=${shown//$build/build} shown=${shown//$work/\$WORK} shown=${shown//$data/\$DATA} shown=${shown//$root\//}
  commands+="$shown"$'\n'
  echo "reproduce_results: $shown" >&2
  nice -n 5 "$@" >"$work/last.log" 2>&1 || { cat "$work/last.log" >&2; echo "reproduce_results: failed: $shown" >&2; exit 1; }
}
wanted() {  # wanted ID QUICK: whether this block runs
  if [ -n "$only" ]; then [[ ",$only," == *",$1,"* ]]; else [ "$quick" = 0 ] || [ "$2" = quick ]; fi
}
begin() { commands="" block_start=$SECONDS; }
finish() {  # finish PAGE ID: the block's content is in $work/ID.md
  printf '%s' "$commands" >"$work/$2.commands"
  $tables splice "$docs/$1" "$2" "$work/$2.md" "$work/$2.commands" "$((SECONDS - block_start))"
  echo "reproduce_results: rewrote $1, block $2 ($((SECONDS - block_start)) s)" >&2
}
have_data() { [ -d "$data/$1" ] || { echo "reproduce_results: $data/$1 absent: block $2 left as it was" >&2; return 1; }; }

# evaluate ID PREFIXES RUN...: each RUN ("name dataset [eval options]") evaluated into $work/ID/name, the runs
# merged by `partreg report`, and the report's tables whose titles start with one of PREFIXES (';'-separated)
# kept as the block's content.
evaluate() {
  local id=$1 prefixes=$2 spec words runs=() titles
  shift 2
  for spec in "$@"; do
    read -r -a words <<<"$spec"
    run "$partreg" eval "${words[1]}" "${words[@]:2}" --threads "$threads" --out "$work/$id/${words[0]}"
    runs+=("$work/$id/${words[0]}")
  done
  run "$partreg" report "${runs[@]}" --out "$work/$id/report"
  IFS=';' read -r -a titles <<<"$prefixes"
  $tables select "$work/$id/report/tables.md" "${titles[@]}" >"$work/$id.md"
}

# benchmark ID PROGRAM [options]: one table of the Google Benchmark program's JSON output, in benchmarks.md.
benchmark() {
  local id=$1 program=$2
  shift 2
  [ -x "$bench/$program" ] || { echo "reproduce_results: no $bench/$program: block $id left as it was" >&2; return 0; }
  begin
  run "$bench/$program" --benchmark_out="$work/$id.json" --benchmark_out_format=json "$@"
  $tables bench "$work/$id.json" >"$work/$id.md"
  finish benchmarks.md "$id"
}

headline="Symmetric RMS distance to the whole true instance;Against the baselines"
parts="Each part against the same part;Seam gap;Largest edge stretch"
labelled_mugs="labelled_mugs $data/mugs --canonical 1a97f3c83016abca21d0de04f408950f --labels $(echo "$root"/assets/labels/*.labels.json)"
one_labelled_mug="mugs $data/mugs --labels $root/assets/labels/1a97f3c83016abca21d0de04f408950f.labels.json"
clean="--views 12 --sweeps none"

# ---- quick blocks: seconds to a minute on two cores (CI runs them into a copy of the docs) ----
if wanted quick-synthetic-mug quick; then
  begin
  run "$partreg" synth mug --instances 4 --seed 1 --out "$work/synthetic_mug"
  evaluate quick-synthetic-mug "$headline;Correspondence error;Sweeps;Time per registration" \
    "synthetic_mug $work/synthetic_mug --protocol quick --variants holistic,hol+part --views 0 --sweeps noise,outliers --levels 5"
  finish results.md quick-synthetic-mug
fi
if wanted quick-cpd quick && have_data drills quick-cpd; then
  benchmark quick-cpd cpd_benchmark --benchmark_filter='/1000/' --benchmark_min_time=0.1
fi
if wanted quick-registration quick && have_data kettles quick-registration; then
  benchmark quick-registration registration_benchmark --benchmark_filter='HolisticOneStart|HolPartOneStart' \
    --benchmark_min_time=0.1
fi

# ---- the full set: on demand ----
if wanted kettles full && have_data kettles kettles; then
  begin
  evaluate kettles "$headline;$parts;Time per registration" "kettles $data/kettles $clean"
  finish results.md kettles
fi
if wanted labelled-mugs full && have_data mugs labelled-mugs; then
  begin
  evaluate labelled-mugs "$headline;$parts;Time per registration" "$labelled_mugs $clean"
  finish results.md labelled-mugs
fi
if wanted synthetic full; then
  begin
  for category in mug spray_bottle drill; do
    run "$partreg" synth "$category" --instances 8 --seed 1 --out "$work/synthetic_${category}s"
  done
  evaluate synthetic "$headline;Correspondence error;Seam gap;Time per registration" \
    "synthetic_mugs $work/synthetic_mugs $clean" "synthetic_spray_bottles $work/synthetic_spray_bottles $clean" \
    "synthetic_drills $work/synthetic_drills $clean"
  finish results-synthetic.md synthetic
fi
if wanted noise-outliers full && have_data kettles noise-outliers && have_data mugs noise-outliers; then
  begin
  level5="--views 12 --sweeps noise,outliers --levels 5 --no-baselines --variants holistic,hol+part,coupled"
  evaluate noise-outliers "Sweeps" "kettles $data/kettles $level5" "$labelled_mugs $level5"
  finish results.md noise-outliers
fi
if wanted depth-scenes full && have_data mugs depth-scenes; then
  begin
  evaluate depth-scenes "Depth scenes" \
    "mugs $data/mugs --protocol paper --variants holistic --sweeps none --views 0 --no-baselines --scenes 3"
  finish results.md depth-scenes
fi
if wanted paper full && have_data kettles paper; then
  begin
  paper="--protocol paper --no-baselines"
  evaluate paper "Table 1;Table 2;Symmetric RMS distance to the whole true instance" \
    "kettles $data/kettles $paper --variants holistic,partwise,hol+part" \
    "$one_labelled_mug $paper --variants holistic,partwise,hol+part" "drills $data/drills $paper --up 0,0,1" \
    "bowls $data/bowls $paper" "bottles $data/bottles $paper" "spatulas $data/spatulas $paper"
  finish results.md paper
fi
if wanted grasps-verdict full && have_data mugs grasps-verdict; then
  begin
  gripper="--gripper $root/assets/grippers/relative_parallel_jaw.json --protocol quick --variants holistic,hol+part --sweeps none"
  evaluate grasps-verdict "Grasps held on the true mesh;A registration is bad when" \
    "mugs $data/mugs $gripper" "bowls $data/bowls $gripper" "bottles $data/bottles $gripper"
  finish results.md grasps-verdict
fi
if wanted evaluation-speed full && have_data kettles evaluation-speed; then
  begin
  evaluate evaluation-speed "Time per registration" "kettles $data/kettles --protocol quick --no-baselines"
  finish benchmarks.md evaluation-speed
fi
if wanted training full && have_data kettles training; then
  begin
  printf '| category | wall s | CPU s (user + system) | peak RSS MB |\n|---|---|---|---|\n' >"$work/training.md"
  for spec in "kettles $data/kettles" "$one_labelled_mug" "drills $data/drills --up 0,0,1" "bowls $data/bowls" \
      "bottles $data/bottles" "spatulas $data/spatulas"; do
    read -r -a words <<<"$spec"
    run /usr/bin/time -f "%e %U %S %M" -o "$work/${words[0]}.time" "$partreg" train "${words[1]}" "${words[@]:2}" \
      --out "$work/${words[0]}.prm"
    read -r wall user system peak <"$work/${words[0]}.time"
    echo "| ${words[0]} | $wall | $(echo "$user + $system" | bc) | $((peak / 1024)) |" >>"$work/training.md"
  done
  finish benchmarks.md training
fi
repeat=(--benchmark_repetitions=3 --benchmark_report_aggregates_only=true)
if wanted cpd full && have_data drills cpd; then benchmark cpd cpd_benchmark "${repeat[@]}"; fi
if wanted registration full && have_data kettles registration; then
  benchmark registration registration_benchmark "${repeat[@]}"
fi
if wanted render full; then benchmark render render_benchmark "${repeat[@]}"; fi
if wanted gui full; then benchmark gui gui_benchmark --benchmark_filter=-Window "${repeat[@]}"; fi

$tables check "${pages[@]/#/$docs/}"
