#!/usr/bin/env bash
# The main job on the embedded default, on a fresh Debian 12 machine: install packages, build, generate a
# synthetic mug category with parts, train its shape spaces, describe the model, and register one synthetic
# mug onto another with non-rigid CPD. Everything it writes goes to ./out/demo.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
bash scripts/build.sh
partreg=./build/partreg
out=out/demo
rm -rf "$out"
mkdir -p "$out"

echo "== 1. a synthetic mug category (body + handle), 8 instances, with ground-truth correspondences" >&2
"$partreg" synth mug --out "$out/mugs" --instances 8 --seed 1

echo "== 2. train its holistic and per-part shape spaces" >&2
"$partreg" train "$out/mugs" --out "$out/mug.prm" --latent 5 --points 1000

echo "== 3. what the model holds" >&2
"$partreg" info "$out/mug.prm"

echo "== 4. non-rigid CPD from one mug to another" >&2
"$partreg" cpd "$out/mugs/mug_000/body.obj" "$out/mugs/mug_001/body.obj" --mode nonrigid --points 1000 \
  --out "$out/mug_000_on_mug_001.ply" --json "$out/cpd.json"

echo "== done: outputs in $out" >&2
ls -l "$out" >&2
