#!/usr/bin/env bash
# The paper's evaluation on every category in ../shared/data and on two synthetic categories, then one merged
# report (real categories first: they are the timed part). Usage: scripts/run_evaluation.sh [paper|quick] [OUT] [THREADS]. Needs a build (scripts/build.sh).
# The tables of docs/results.md come from scripts/reproduce_results.sh, which runs its own declared set.
set -euo pipefail
cd "$(dirname "$0")/.."
protocol=${1:-paper}
out=${2:-out/evaluation}
threads=${3:-0}
data=${PARTREG_DATA_DIR:-../shared/data}
partreg=./build/partreg
if [ -e "$out" ]; then echo "run_evaluation: $out exists; remove it or choose another folder" >&2; exit 2; fi
mkdir -p "$out/runs"

run() {  # run NAME DATASET [extra eval options...]
  local name=$1 dataset=$2
  shift 2
  echo "== $name" >&2
  /usr/bin/time -f "$name: %e s wall, %U s user" "$partreg" eval "$dataset" --protocol "$protocol" \
    --threads "$threads" --out "$out/runs/$name" "$@"
}

if [ -d "$data" ]; then
  run kettles "$data/kettles"
  run mugs "$data/mugs" --labels assets/labels/1a97f3c83016abca21d0de04f408950f.labels.json
  run drills "$data/drills" --up 0,0,1  # drills stand on z (their README); the others are y up
  for category in bowls bottles spatulas; do run "$category" "$data/$category"; done
else
  echo "run_evaluation: $data is absent: only the synthetic categories are evaluated" >&2
fi
if [ "${PARTREG_EVAL_SYNTHETIC:-1}" = 1 ]; then
  "$partreg" synth mug --instances 8 --seed 1 --out "$out/synthetic/synthetic_mugs"
  "$partreg" synth spray_bottle --instances 8 --seed 1 --out "$out/synthetic/synthetic_spray_bottles"
  "$partreg" synth drill --instances 8 --seed 1 --out "$out/synthetic/synthetic_drills"
  run synthetic_mugs "$out/synthetic/synthetic_mugs"
  run synthetic_spray_bottles "$out/synthetic/synthetic_spray_bottles"
  run synthetic_drills "$out/synthetic/synthetic_drills"
fi
"$partreg" report "$out"/runs/* --out "$out/report"
echo "report: $out/report/tables.md and $out/report/*.png" >&2
