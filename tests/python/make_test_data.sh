#!/usr/bin/env bash
# The command line's results that the Python tests must reproduce (to 1e-9), on real data: a mug model with
# parts (committed labels), a hol+part registration of a real mug with its mesh, points and a grasp frame,
# rigid and non-rigid CPD between two real drills, and partial views of a mug.
# Usage: make_test_data.sh PARTREG SOURCE_DIR DATA_DIR OUT_DIR. Exit 77 (skip) without the shared data.
set -euo pipefail
partreg=$1 source_dir=$2 data_dir=$3 out=$4
[ -d "$data_dir/mugs" ] && [ -d "$data_dir/drills" ] || { echo "shared data absent: $data_dir"; exit 77; }
rm -rf "$out" && mkdir -p "$out"
mug=$data_dir/mugs/5c48d471200d2bf16e8a121e6886e18d.obj
"$partreg" train "$data_dir/mugs" --labels "$source_dir/assets/labels/1a97f3c83016abca21d0de04f408950f.labels.json" \
  --out "$out/mugs.prm" --points 500 --samples 2000 --json "$out/train.json" 2>"$out/train.log"
"$partreg" register "$out/mugs.prm" "$mug" --variant hol+part --json "$out/register.json" \
  --points-out "$out/register_points.ply" --mesh-out "$out/register_mesh.ply" \
  --frames "$source_dir/assets/frames/mug_handle_grasp.json" --frames-out "$out/register_frames.json" \
  --truth "$data_dir/mugs/1a97f3c83016abca21d0de04f408950f.obj" 2>"$out/register.log"
"$partreg" cpd "$data_dir/drills/drill_1.pcd" "$data_dir/drills/drill_2.pcd" --mode rigid --out "$out/cpd_rigid.ply" \
  --json "$out/cpd_rigid.json" 2>"$out/cpd_rigid.log"
"$partreg" cpd "$data_dir/drills/drill_1.pcd" "$data_dir/drills/drill_2.pcd" --mode nonrigid --out "$out/cpd_nonrigid.ply" \
  --json "$out/cpd_nonrigid.json" 2>"$out/cpd_nonrigid.log"
"$partreg" views "$data_dir/mugs/1a97f3c83016abca21d0de04f408950f.obj" --count 12 --out "$out/views" 2>"$out/views.log"
# One depth view of the observed mug, for the Open3D example, and the camera position it was seen from.
"$partreg" views "$mug" --count 12 --resolution 320x240 --out "$out/observed_views" 2>"$out/observed_views.log"
python3 -c 'import json, sys; print(",".join(repr(v) for v in json.load(open(sys.argv[1]))["views"][0]["viewpoint"]))' \
  "$out/observed_views/views.json" >"$out/observed_viewpoint.txt"
echo "test data in $out"
