#!/usr/bin/env bash
# partreg against Interaction Warping: the same held-out ShapeNet mugs and bowls, the same
# observation files, both scored by partreg's own error code at equal point density.
#
# It fetches nothing. Give it these source folders (all MIT), checked out outside the repository:
#   --peer DIR     https://github.com/ondrejbiza/shapewarping  (its shapewarping/ package; a full checkout may
#                  fail on a missing v-hacd binary, `git archive HEAD shapewarping | tar -x -C DIR` is enough)
#   --cycpd DIR    https://github.com/gattia/cycpd            (the peer's CPD; Cython, built here in WORK)
#   --trimesh DIR  https://github.com/mikedh/trimesh          (the peer's mesh library; pure Python)
# From Debian (apt-get install -y ...): python3-torch (1.13, CPU), python3-sklearn, python3-scipy,
# python3-numpy, python3-plotly, python3-open3d (imported by the peer's viz_utils), cython3, python3-dev.
# The partreg Python module (build/python, PARTREG_BUILD_PYTHON) makes the full views and scores everything.
# The peer runs from a copy in WORK with two changes that do not touch its method: `pybullet` (imported at the
# top of its utils for simulator helpers training and inference never call; not in Debian) is an empty module,
# and its ObjParam dataclass gets its numpy defaults through default_factory (Python 3.11 refuses mutable
# defaults; the peer pins no interpreter).
#
# Usage: scripts/bench_interaction_warping.sh --peer DIR --cycpd DIR --trimesh DIR [--work DIR]
#            [--partreg BIN] [--python-module DIR] [--folds "CATEGORY:HELD,OUT ..."] [--jobs N]
#            [--peer-threads N]
#
# Protocol. Each fold holds out instances of a category folder of ../shared/data (default: two folds of two
# mugs, one of two bowls: 4 mugs and 2 bowls); both methods train on the rest with their defaults
# (`partreg train`; the peer's `learn_warp`, turned y up -> z up since its search turns about z, with its 8 PCA
# dimensions capped at its number of warps, training meshes - 1: sklearn refuses more). Each held-out
# instance gives three observation files, used by both: the full view (2000 area-uniform surface samples,
# seed 1) and partial views 0 and 6 of `partreg views --count 12` (the quick protocol's swept views), clean.
# partreg: `register` with its defaults. The peer: its own inference settings (PARAM_1, 12 starting yaws,
# one batch, observation farthest-point sampled to 2000; scripts/interaction_warping_peer.py). Score: each
# deformed mesh (partreg's canonical mesh, the peer's canonical mesh) sampled to 4000 points, symmetric RMS
# against the truth sampled as `register --truth` does (scripts/score_deformed_meshes.py); partreg's own
# figure on its M canonical points is listed too. CPU: user + system seconds, one thread each (partreg: the
# whole `register --threads 1` process without --truth; the peer, OMP_NUM_THREADS=1 unless --peer-threads:
# the process CPU time of its inference, all threads, without the Python start-up; its trainings run with
# its default threads). The peer's trainings, then its inferences (full views first)
# run --jobs at a time (default 2). Outputs already in WORK are reused, so a stopped run resumes.
# The tables go to WORK/table.md.
set -euo pipefail
python=/usr/bin/python3  # Debian's, where python3-torch is
peer_src='' cycpd_src='' trimesh_src='' work=${TMPDIR:-/tmp}/partreg_iw partreg=./build/partreg module=./build/python jobs=2 peer_threads=1
folds="mugs:1a97f3c83016abca21d0de04f408950f,1c9f9e25c654cbca3c71bf3f4dd78475
mugs:1eaf8db2dd2b710c7d5b1b70ae595e60,3d1754b7cb46c0ce5c8081810641ef6
bowls:1b4d7803a3298f8477bdcb8816a3fac9,1fbb9f70d081630e638b4be15b07b442"
while [ $# -gt 0 ]; do
  [ $# -ge 2 ] || { echo "usage: see the header of $0" >&2; exit 2; }
  case $1 in
    --peer) peer_src=$2 ;; --cycpd) cycpd_src=$2 ;; --trimesh) trimesh_src=$2 ;; --work) work=$2 ;;
    --partreg) partreg=$2 ;; --python-module) module=$2 ;; --folds) folds=$2 ;; --jobs) jobs=$2 ;;
    --peer-threads) peer_threads=$2 ;;
    *) echo "usage: see the header of $0" >&2; exit 2 ;;
  esac
  shift 2
done
[[ $jobs =~ ^[1-9][0-9]*$ && $peer_threads =~ ^[1-9][0-9]*$ ]] ||
  { echo "$0: --jobs and --peer-threads are positive counts" >&2; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd)
data=${PARTREG_DATA_DIR:-$here/../shared/data}
for d in "$peer_src/shapewarping" "$cycpd_src/cycpd" "$trimesh_src/trimesh"; do
  [ -d "$d" ] || { echo "$0: no $d (give --peer, --cycpd and --trimesh: see the header)" >&2; exit 2; }
done
[ -x "$partreg" ] || { echo "$0: no partreg binary at $partreg (--partreg)" >&2; exit 2; }
[ -d "$module/partreg" ] || { echo "$0: no partreg Python module under $module (--python-module)" >&2; exit 2; }
case $(realpath -m "$work")/ in "$here"/*) echo "$0: --work must be outside the repository" >&2; exit 2 ;; esac
partreg=$(realpath "$partreg") module=$(realpath "$module")
mkdir -p "$work"
work=$(realpath "$work")

# --- the peer's copy and its dependencies (once) ---
if [ ! -f "$work/deps/ready" ]; then
  rm -rf "$work/peer" "$work/deps"
  mkdir -p "$work/peer" "$work/deps/shim"
  cp -r "$peer_src/shapewarping" "$work/peer/"
  "$python" - "$work/peer/shapewarping/lib/utils.py" <<'PY'
import re, sys
path = sys.argv[1]
text = open(path).read()
text = text.replace("from dataclasses import dataclass\n", "from dataclasses import dataclass, field\n", 1)
text, count = re.subn(r"^(    \w+: \w+) = (np\.array\(.*\))$", r"\1 = field(default_factory=lambda: \2)", text,
                      flags=re.M)
if count != 3:
    sys.exit(f"expected the 3 numpy defaults of ObjParam in {path}, found {count}")
open(path, "w").write(text)
PY
  echo "# Empty: the peer's utils import pybullet for simulator helpers this benchmark never calls." \
    > "$work/deps/shim/pybullet.py"
  cp -r "$cycpd_src" "$work/deps/cycpd"
  (cd "$work/deps/cycpd" && "$python" setup.py build_ext --inplace >"$work/deps/cycpd_build.log" 2>&1)
  touch "$work/deps/ready"
fi
peer_path=$work/peer:$(realpath "$trimesh_src"):$work/deps/cycpd:$work/deps/shim

# --- partreg and the observations, per fold (cheap) ---
results=$work/rows.txt
: > "$results"
peer_trainings=() peer_inferences=()
for fold in $folds; do
  category=${fold%%:*} held=${fold#*:}
  id=${category}_${held:0:4}
  train=$work/train_$id
  if [ ! -d "$train" ]; then
    mkdir -p "$train.tmp"
    for mesh in "$data/$category"/*.obj; do
      name=$(basename "$mesh" .obj)
      [[ ,$held, == *,$name,* ]] || ln -s "$mesh" "$train.tmp/$name.obj"
    done
    mv "$train.tmp" "$train"
  fi
  [ -f "$work/partreg_$id.prm" ] ||
    /usr/bin/time -f '%U %S %e' -o "$work/partreg_$id.train_time" "$partreg" train "$train" \
      --out "$work/partreg_$id.prm" -q
  [ -f "$work/peer_$id.pkl" ] || peer_trainings+=("$id")
  echo "train $id $work/partreg_$id.train_time $work/peer_$id.train_time" >> "$results"
  for name in ${held//,/ }; do
    truth=$data/$category/$name.obj
    o=$work/obs/$name
    if [ ! -f "$o/view006.ply" ]; then
      rm -rf "$o" && mkdir -p "$o"
      PYTHONPATH=$module "$python" -c "import partreg, sys
partreg.write_cloud(sys.argv[2], partreg.read_cloud(sys.argv[1], mesh_samples=2000, seed=1))" "$truth" "$o/full.ply"
      "$partreg" views "$truth" --count 12 --out "$o/views" -q
      cp "$o/views/view_000.ply" "$o/view000.ply" && cp "$o/views/view_006.ply" "$o/view006.ply"
    fi
    for view in full view000 view006; do
      r=$o/$view
      if [ ! -f "$r.partreg.time" ]; then  # written last
        "$partreg" register "$work/partreg_$id.prm" "$o/$view.ply" --truth "$truth" --mesh-out "$r.partreg.ply" \
          --points-out "$r.partreg_points.ply" --json "$r.partreg.json" -q
        /usr/bin/time -f '%U %S %e' -o "$r.partreg.time.tmp" "$partreg" register "$work/partreg_$id.prm" \
          "$o/$view.ply" --threads 1 --json "$r.partreg_timed.json" -q
        mv "$r.partreg.time.tmp" "$r.partreg.time"
      fi
      [ -f "$r.peer.json" ] || peer_inferences+=("$view $id $r")
      echo "obs $category $name $view $r $truth" >> "$results"
    done
  done
done

# --- the peer (expensive): trainings, then inferences, full views first, --jobs at a time ---
# The peer's PCA has 8 dimensions by default and sklearn refuses more than it has warps (training meshes - 1).
peer_dimensions() { local count; count=$(find "$work/train_$1" -name '*.obj' | wc -l); echo $((count > 9 ? 8 : count - 1)); }
peer_train() {  # ID
  PYTHONPATH=$peer_path /usr/bin/time -f '%U %S %e' -o "$work/peer_$1.train_time" \
    "$python" -m shapewarping.learn_warp "$work/train_$1" "$work/peer_$1.pkl.tmp" --rot-x 1.5707963267948966 \
    --n-dimensions "$(peer_dimensions "$1")" >"$work/peer_$1.train_log" 2>&1
  mv "$work/peer_$1.pkl.tmp" "$work/peer_$1.pkl"
}
peer_infer() {  # VIEW ID STEM
  PYTHONPATH=$peer_path OMP_NUM_THREADS=$peer_threads "$python" "$here/scripts/interaction_warping_peer.py" infer \
    "$work/peer_$2.pkl" "$work/train_$2" "$3.ply" "$3.peer.ply" "$3.peer_json.tmp" 2>"$3.peer.log"
  mv "$3.peer_json.tmp" "$3.peer.json"
}
at_most_jobs() { while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n; done; }
for id in "${peer_trainings[@]}"; do at_most_jobs; peer_train "$id" & done
wait
for view in full view000 view006; do
  for job in "${peer_inferences[@]}"; do
    read -r v id stem <<< "$job"
    [ "$v" = "$view" ] || continue
    at_most_jobs; peer_infer "$view" "$id" "$stem" &
  done
done
wait
while read -r kind category name view stem truth; do
  [ "$kind" = obs ] || continue
  peer_mesh=() && [ -f "$stem.peer.json" ] && peer_mesh=("$stem.peer.ply")  # a failed inference: no column
  PYTHONPATH=$module "$python" "$here/scripts/score_deformed_meshes.py" "$truth" "$stem.partreg.ply" \
    "$stem.partreg_points.ply" "${peer_mesh[@]}" > "$stem.scores"
done < "$results"

# --- the tables ---
"$python" - "$results" > "$work/table.md" <<'PY'
import json, os, sys
from collections import defaultdict
rows = [line.split() for line in open(sys.argv[1]) if line.strip()]
pct = lambda x: f"{100 * x:.2f}"
def cpu(path):  # user + system seconds from /usr/bin/time -f '%U %S %e'
    user, system, _ = open(path).read().split()[-3:]
    return float(user) + float(system)
print("Training, CPU s: " + "; ".join(f"{r[1]}: partreg {cpu(r[2]):.1f}, peer {cpu(r[3]):.0f}"
                                      for r in rows if r[0] == "train" and os.path.exists(r[3])))
print()
print("| category | instance | view | partreg | partreg, own M points | Interaction Warping | lower | "
      "partreg CPU s | peer CPU s |")
print("|---|---|---|---|---|---|---|---|---|")
groups = defaultdict(list)
for _, category, name, view, stem, _ in (r for r in rows if r[0] == "obs"):
    scores = [json.loads(line)["symmetric_rms_per_diagonal"] for line in open(stem + ".scores")]
    partreg_cpu = cpu(stem + ".partreg.time")
    if len(scores) < 3:  # the peer did not finish this one
        print(f"| {category} | {name[:8]} | {view} | {pct(scores[0])} | {pct(scores[1])} | not run | | "
              f"{partreg_cpu:.2f} | |")
        continue
    mesh, own, peer = scores
    peer_cpu = json.load(open(stem + ".peer.json"))["cpu_seconds"]
    print(f"| {category} | {name[:8]} | {view} | {pct(mesh)} | {pct(own)} | {pct(peer)} | "
          f"{'partreg' if mesh < peer else 'peer'} | {partreg_cpu:.2f} | {peer_cpu:.0f} |")
    groups[(category, "full" if view == "full" else "partial")].append((mesh, own, peer, partreg_cpu, peer_cpu))
print()
print("| category, views | observations | partreg | partreg, own M points | Interaction Warping | "
      "partreg / peer | partreg lower on | partreg CPU s | peer CPU s |")
print("|---|---|---|---|---|---|---|---|---|")
for (category, kind), g in sorted(groups.items()):
    mean = lambda i: sum(x[i] for x in g) / len(g)
    wins = sum(x[0] < x[2] for x in g)
    print(f"| {category}, {kind} | {len(g)} | {pct(mean(0))} | {pct(mean(1))} | {pct(mean(2))} | "
          f"{mean(0) / mean(2):.2f} | {wins} of {len(g)} | {mean(3):.2f} | {mean(4):.0f} |")
PY
cat "$work/table.md"
