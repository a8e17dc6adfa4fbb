#!/usr/bin/env bash
# Submits the evaluation of DATASET as a Slurm job array of SHARDS shards (scripts/eval_slurm.sbatch) and the
# merge as a dependent job that runs only when every shard succeeded. OUT must be on a file system every
# node sees. Prints the two job ids.
# Usage: scripts/eval_slurm_submit.sh [--wait] PARTREG DATASET OUT SHARDS [EVAL OPTIONS...]
#   --wait  return only when the merge has ended, with its status (a failed shard cancels the merge where
#           Slurm has DependencyParameters=kill_invalid_depend, as scripts/slurm_local.sh sets)
set -euo pipefail
wait=()
[ "${1:-}" = --wait ] && { wait=(--wait); shift; }
[ $# -ge 4 ] || { echo "usage: $0 [--wait] PARTREG DATASET OUT SHARDS [EVAL OPTIONS...]" >&2; exit 2; }
partreg=$(realpath "$1") dataset=$(realpath "$2") out=$(realpath -m "$3") shards=$4
shift 4
[[ $shards =~ ^[1-9][0-9]*$ ]] || { echo "$0: SHARDS must be a positive integer, got '$shards'" >&2; exit 2; }
[ -e "$out" ] && { echo "$0: $out exists; give a new folder" >&2; exit 2; }
mkdir -p "$out/shards"
here=$(dirname "$(realpath "$0")")
array=$(PARTREG=$partreg DATASET=$dataset OUT=$out SHARDS=$shards EVAL_OPTIONS="$*" \
  sbatch --parsable --export=ALL --array="1-$shards" --chdir="$out" "$here/eval_slurm.sbatch")
echo "shards: job array $array" >&2
merge=$(sbatch --parsable "${wait[@]}" --dependency="afterok:${array%%;*}" --job-name=partreg-report --chdir="$out" \
  --output=report-%j.log --wrap="\"$partreg\" report \"$out\"/shards/* --out \"$out/merged\"")
echo "shards: job array $array; merge: job $merge (after every shard succeeded)"
