#!/usr/bin/env bash
# Fails when an installed public header includes anything but the C++ standard library, Eigen, nlohmann_json
# and partreg itself: no PCL, assimp, GL, Ceres, Embree, cairo, OSMesa or GLFW type can reach a user.
# Usage: check_public_headers.sh INCLUDE_DIR   (INCLUDE_DIR/partreg/... as installed)
set -euo pipefail
include_dir=$1
[ -d "$include_dir/partreg" ] || { echo "no headers under $include_dir/partreg"; exit 1; }
headers=$(find "$include_dir/partreg" -name '*.hpp' | sort)
[ -n "$headers" ] || { echo "no headers under $include_dir/partreg"; exit 1; }
allowed='^#include (<[a-z_]+>|<Eigen/[A-Za-z]+>|<nlohmann/json\.hpp>|"partreg/[a-z_/]+\.hpp")$'
bad=$(grep -H '^[[:space:]]*#[[:space:]]*include' $headers | sed 's/:[[:space:]]*#[[:space:]]*include[[:space:]]*/:#include /' |
      awk -F: -v allowed="$allowed" '{ line = $0; sub(/^[^:]*:/, "", line); if (line !~ allowed) print }') || true
if [ -n "$bad" ]; then
  echo "public headers include what users must not need:"
  echo "$bad"
  exit 1
fi
echo "$(echo "$headers" | wc -l) public headers include only the standard library, Eigen, nlohmann_json and partreg"
