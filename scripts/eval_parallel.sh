#!/usr/bin/env bash
# Runs `partreg eval` as SHARDS shards under GNU parallel on this machine (Debian package `parallel`), then merges
# them with `partreg report`: OUT/shards/I holds shard I's eval output, OUT/merged the merged tables.
# Usage: scripts/eval_parallel.sh [--partreg BIN] [--jobs J] DATASET OUT SHARDS [EVAL OPTIONS...]
#   --partreg  the partreg executable (default ./build/partreg)
#   --jobs     shards run at once (default SHARDS); each gets --threads (cores / jobs) unless EVAL OPTIONS set it
# Anything after SHARDS goes to every `partreg eval` unchanged (--protocol, --variants, --labels, ...).
set -euo pipefail
partreg=./build/partreg jobs=
while [ $# -gt 0 ]; do
  case $1 in
    --partreg) partreg=$2; shift 2 ;;
    --jobs) jobs=$2; shift 2 ;;
    *) break ;;
  esac
done
[ $# -ge 3 ] || { echo "usage: $0 [--partreg BIN] [--jobs J] DATASET OUT SHARDS [EVAL OPTIONS...]" >&2; exit 2; }
dataset=$1 out=$2 shards=$3
shift 3
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "$0: SHARDS must be a positive integer, got '$shards'" >&2; exit 2; }
[ -e "$out" ] && { echo "$0: $out exists; give a new folder" >&2; exit 2; }
command -v parallel >/dev/null || { echo "$0: GNU parallel is not installed (apt-get install parallel)" >&2; exit 1; }
jobs=${jobs:-$shards}
threads=()
[[ " $* " == *" --threads "* ]] || threads=(--threads "$(( $(nproc) / jobs > 0 ? $(nproc) / jobs : 1 ))")
mkdir -p "$out/shards"
# --halt now,fail=1: one failed shard stops the others; the merge then does not run.
parallel --will-cite --halt now,fail=1 --jobs "$jobs" --line-buffer --tagstring 'shard {}' \
  "$partreg" eval "$dataset" --out "$out/shards/{}" --shard "{}/$shards" "${threads[@]}" "$@" \
  ::: $(seq 1 "$shards")
"$partreg" report "$out"/shards/* --out "$out/merged"
