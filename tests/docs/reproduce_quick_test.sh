#!/usr/bin/env bash
# scripts/reproduce_results.sh --quick into a copy of the pages: it must rewrite the quick blocks with a stamp
# of today and this source tree's commit, leave the tracked pages alone, and its checker must refuse a table
# without a stamp. Usage: reproduce_quick_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1 build_dir=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/docs"
pages=("$source_dir"/docs/{results,results-synthetic,benchmarks}.md)
cp "${pages[@]}" "$work/docs/"
before=$(cat "${pages[@]}" | md5sum)

bash "$source_dir/scripts/reproduce_results.sh" --quick --build "$build_dir" --docs "$work/docs" --threads 2

after=$(cat "${pages[@]}" | md5sum)
[ "$before" = "$after" ] || { echo "the tracked pages changed" >&2; exit 1; }
commit=$(git -C "$source_dir" rev-parse --short HEAD)
today=$(date -u +%Y-%m-%d)
block=$(sed -n '/<!-- BEGIN GENERATED quick-synthetic-mug -->/,/<!-- END GENERATED quick-synthetic-mug -->/p' \
  "$work/docs/results.md")
grep -q "^Generated: commit $commit\(+local changes\)\?, $today " <<<"$block" ||
  { echo "the quick block carries no stamp of today and commit $commit:" >&2; echo "$block" >&2; exit 1; }
grep -q "partreg eval .* --protocol quick" <<<"$block" || { echo "the quick block names no eval command" >&2; exit 1; }
grep -q "^| synthetic_mug | [0-9]" <<<"$block" || { echo "the quick block has no figures" >&2; exit 1; }

printf '# A page\n\n| a | b |\n|---|---|\n| 1 | 2 |\n' >"$work/unstamped.md"
if /usr/bin/python3 "$source_dir/scripts/results_tables.py" check "$work/unstamped.md" 2>/dev/null; then
  echo "the checker accepted a table without a stamp" >&2
  exit 1
fi
echo "quick blocks regenerated into a copy; the tracked pages unchanged"
