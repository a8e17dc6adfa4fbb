#!/usr/bin/env bash
# Runs every ```sh block of README.md's "Commands" section, in order, in a scratch folder that looks like the
# repository root (build/ and assets/ linked, ../shared/data pointing at the configured data). Exit 77 (skip)
# without the shared data.
set -euo pipefail
source_dir=$1 binary_dir=$2 data_dir=$3
[ -d "$data_dir" ] || { echo "shared data absent: $data_dir"; exit 77; }
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
mkdir -p "$scratch/root" "$scratch/shared"
ln -s "$binary_dir" "$scratch/root/build"
ln -s "$source_dir/assets" "$scratch/root/assets"
ln -s "$(realpath "$data_dir")" "$scratch/shared/data"
awk '/^## /{on=($0 == "## Commands")} on && /^```sh/{block=1; next} block && /^```/{block=0; next} block' \
  "$source_dir/README.md" > "$scratch/commands.sh"
[ -s "$scratch/commands.sh" ] || { echo "no commands found in README.md"; exit 1; }
cd "$scratch/root"
echo "running $(grep -c 'partreg ' "$scratch/commands.sh") README commands"
bash -euxo pipefail "$scratch/commands.sh"
