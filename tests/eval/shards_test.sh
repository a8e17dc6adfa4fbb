#!/usr/bin/env bash
# The evaluation's shards, run under GNU parallel by scripts/eval_parallel.sh and merged by `partreg report`,
# give the unsharded run's rows and tables bit for bit (timings aside), at another thread count too (the
# unsharded run uses 2 threads, each shard 1). A difference in the last digit of one row fails it.
# Usage: shards_test.sh SOURCE_DIR PARTREG [SCHEDULER]   SCHEDULER: parallel (default) or slurm
set -euo pipefail
source_dir=$1 partreg=$2 scheduler=${3:-parallel}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

"$partreg" synth mug --out "$work/mugs" --instances 4 --seed 3 --correspondences 300 --quiet
options=(--protocol quick --variants holistic --folds 2 --levels 3 --quiet)
"$partreg" eval "$work/mugs" --out "$work/whole" --threads 2 "${options[@]}"
case $scheduler in
  parallel)
    command -v parallel >/dev/null || { echo "SKIP: GNU parallel is not installed (apt-get install parallel)"; exit 77; }
    bash "$source_dir/scripts/eval_parallel.sh" --partreg "$partreg" --jobs 2 "$work/mugs" "$work/sharded" 2 \
      --threads 1 "${options[@]}" ;;
  slurm)
    bash "$source_dir/scripts/slurm_local.sh" check || exit 77
    bash "$source_dir/scripts/slurm_local.sh" run "$work/slurm" \
      bash "$source_dir/scripts/eval_slurm_submit.sh" --wait "$partreg" "$work/mugs" "$work/sharded" 2 \
      "${options[@]}" ;;
  *) echo "unknown scheduler $scheduler" >&2; exit 2 ;;
esac

# Rows in a canonical order without their time (column 24, `seconds`); tables up to the timing table.
rows() { tail -n +2 "$1/results.csv" | awk -F, -v OFS=, '{ $24 = "" } 1' | LC_ALL=C sort; }
tables() { sed '/^Time per registration/,$d' "$1/tables.md"; }
[ "$(rows "$work/whole" | wc -l)" -gt 50 ] || { echo "FAIL: the unsharded run has too few rows"; exit 1; }
status=0
if ! diff <(rows "$work/whole") <(rows "$work/sharded/merged") >"$work/rows.diff"; then
  echo "FAIL: merged shard rows differ from the unsharded run's ($(grep -c '^<' "$work/rows.diff") rows):"
  head -4 "$work/rows.diff"
  status=1
fi
if ! diff <(tables "$work/whole") <(tables "$work/sharded/merged"); then
  echo "FAIL: merged tables differ from the unsharded run's"
  status=1
fi
[ $status -eq 0 ] && echo "$(rows "$work/whole" | wc -l) rows and the tables agree exactly ($scheduler, 2 shards)"
exit $status
