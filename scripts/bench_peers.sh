#!/usr/bin/env bash
# Side-by-side CPD benchmark: partreg and its peers, interleaved, on the same normalised inputs.
#
# It fetches nothing. Give it the peers' source folders (any that are missing are left out of the table):
#   BCPD          https://github.com/ohirose/bcpd      (C; needs gcc with OpenMP and libopenblas-dev)
#   gadomski/cpd  https://github.com/gadomski/cpd      (C++; needs cmake and libeigen3-dev)
#   pycpd         https://github.com/siavashk/pycpd    (Python; needs python3-numpy and python3-scipy)
# The peers are built in WORK (outside the repository), never in it.
#
# Usage: scripts/bench_peers.sh [--bcpd DIR] [--gadomski DIR] [--pycpd DIR] [--work DIR] [--partreg BIN]
#                               [--mode nonrigid|rigid] [--sizes "500 1000 2000 5000"] [--cpu-limit SECONDS]
# Sizes default to 500 1000 2000 5000; 20000 and 100000 are optional (give them in --sizes: the slow peers
# take hours there, so --cpu-limit, default 600 CPU seconds a run (ulimit -t: CPU time, so a loaded machine
# does not cut a peer short), stops a run and the table says so). A run that exits without writing its output
# is marked no_output; BCPD's question whether to go on without acceleration for a large set is answered yes.
#
# Inputs: drills/drill_1.pcd (source) and drill_2.pcd (target) from ../shared/data (or PARTREG_DATA_DIR),
# each centred and scaled to a unit bounding-box diagonal, densified to the size by copies with 0.2%
# Gaussian jitter (or farthest-point subsampled). Non-rigid: beta = lambda = 2, w = 0.1, tolerance 1e-5,
# at most 150 iterations; rigid: w = 0.1, tolerance 1e-6. For each size the implementations run one after
# another (interleaved), BCPD both with (BCPD-A, -A) and without its acceleration, and the table gives CPU seconds (user + system), wall seconds, peak memory
# (/usr/bin/time), the fit (mean distance from each moved source point to the nearest target point, as a
# share of the diagonal) and the CPU ratio to the fastest peer (partreg's CPU / the fastest peer's).
set -euo pipefail
python=${PYTHON:-/usr/bin/python3}  # Debian's, with python3-numpy and python3-scipy
bcpd_src= gadomski_src= pycpd_src= work=${TMPDIR:-/tmp}/partreg_peers partreg=./build/partreg
mode=nonrigid sizes="500 1000 2000 5000" cpu_limit_s=600
while [ $# -gt 0 ]; do
  case $1 in
    --bcpd) bcpd_src=$2 ;; --gadomski) gadomski_src=$2 ;; --pycpd) pycpd_src=$2 ;; --work) work=$2 ;;
    --partreg) partreg=$2 ;; --mode) mode=$2 ;; --sizes) sizes=$2 ;; --cpu-limit) cpu_limit_s=$2 ;;
    *) echo "usage: see the header of $0" >&2; exit 2 ;;
  esac
  shift 2
done
[[ $mode == nonrigid || $mode == rigid ]] || { echo "$0: --mode is nonrigid or rigid" >&2; exit 2; }
here=$(cd "$(dirname "$0")/.." && pwd)
data=${PARTREG_DATA_DIR:-$here/../shared/data}
[ -f "$data/drills/drill_1.pcd" ] || { echo "$0: no drills under $data" >&2; exit 1; }
partreg=$(realpath "$partreg")
mkdir -p "$work/build" "$work/inputs" "$work/out"
case $(realpath -m "$work")/ in "$here"/*) echo "$0: --work must be outside the repository" >&2; exit 2 ;; esac

# --- build the peers (once) ---
if [ -n "$bcpd_src" ] && [ ! -x "$work/build/bcpd" ]; then
  (cd "$bcpd_src" && gcc -O3 -fopenmp -DUSE_OPENMP register/*.c base/*.c -lopenblas -lm -o "$work/build/bcpd")
fi
if [ -n "$gadomski_src" ] && [ ! -x "$work/build/gadomski_cpd" ]; then
  cmake -S "$gadomski_src" -B "$work/build/gadomski" -DCMAKE_BUILD_TYPE=Release -DWITH_TESTS=OFF \
    -DWITH_DOCS=OFF -DWITH_JSONCPP=OFF -DWITH_FGT=OFF -DWITH_STRICT_WARNINGS=OFF >/dev/null
  cmake --build "$work/build/gadomski" --parallel "$(nproc)" >/dev/null
  # A file-to-file driver: gadomski/cpd is a library only.
  cat > "$work/build/gadomski_driver.cpp" <<'CPP'
#include <cpd/nonrigid.hpp>
#include <cpd/rigid.hpp>
#include <cpd/utils.hpp>
#include <fstream>
#include <string>
int main(int argc, char** argv) {  // MODE TARGET SOURCE OUT
  const std::string mode = argv[1];
  const cpd::Matrix target = cpd::matrix_from_path(argv[2]), source = cpd::matrix_from_path(argv[3]);
  cpd::Matrix moved;
  if (mode == "rigid") {
    cpd::Rigid rigid;
    rigid.outliers(0.1).tolerance(1e-6).max_iterations(150);
    moved = rigid.run(target, source).points;
  } else {
    cpd::Nonrigid nonrigid;
    nonrigid.beta(2.0).lambda(2.0).outliers(0.1).tolerance(1e-5).max_iterations(150);
    moved = nonrigid.run(target, source).points;
  }
  std::ofstream(argv[4]) << moved << "\n";
}
CPP
  g++ -O3 -std=c++14 -I"$gadomski_src/include" -I/usr/include/eigen3 "$work/build/gadomski_driver.cpp" \
    "$work/build/gadomski"/libcpd.a -o "$work/build/gadomski_cpd" 2>/dev/null ||
    g++ -O3 -std=c++14 -I"$gadomski_src/include" -I/usr/include/eigen3 "$work/build/gadomski_driver.cpp" \
      $(find "$work/build/gadomski" -name 'libcpd*.a' -o -name 'libcpd*.so' | head -1) -o "$work/build/gadomski_cpd"
fi

# --- inputs: normalised, densified drills as plain text (x y z per line) ---
"$python" - "$data/drills" "$work/inputs" $sizes <<'PY'
import sys, numpy as np
src, out, sizes = sys.argv[1], sys.argv[2], [int(s) for s in sys.argv[3:]]
def read_pcd(path):
    lines = open(path).read().splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith('DATA')) + 1
    return np.array([[float(v) for v in l.split()[:3]] for l in lines[start:] if l.strip()])
def normalised(p):
    lo, hi = p.min(0), p.max(0)
    return (p - (lo + hi) / 2) / np.linalg.norm(hi - lo)
def at_size(p, n, rng):
    if n <= len(p):  # farthest points
        chosen, d = [0], np.sum((p - p[0]) ** 2, 1)
        while len(chosen) < n:
            chosen.append(int(np.argmax(d))); d = np.minimum(d, np.sum((p - p[chosen[-1]]) ** 2, 1))
        return p[chosen]
    extra = p[rng.integers(0, len(p), n - len(p))] + rng.normal(0.0, 0.002, (n - len(p), 3))
    return np.vstack([p, extra])
rng = np.random.default_rng(3)
source, target = normalised(read_pcd(src + '/drill_1.pcd')), normalised(read_pcd(src + '/drill_2.pcd'))
for n in sizes:
    np.savetxt(f'{out}/source_{n}.txt', at_size(source, n, rng), fmt='%.8f')
    np.savetxt(f'{out}/target_{n}.txt', at_size(target, n, rng), fmt='%.8f')
    with open(f'{out}/source_{n}.xyz', 'w') as f: f.write(open(f'{out}/source_{n}.txt').read())
    with open(f'{out}/target_{n}.xyz', 'w') as f: f.write(open(f'{out}/target_{n}.txt').read())
PY

# --- one run: NAME SIZE OUTPUT-FILE COMMAND...; appends "name size cpu wall peak_mb status output" ---
# The command runs under a CPU-time limit (RLIMIT_CPU: SIGXCPU, then SIGKILL), with "y" lines on its input
# (BCPD asks before a large set without acceleration; on an empty input it prints "Abort" and exits 0).
results=$work/results.txt
: > "$results"
yes y 2>/dev/null | head -n 100 > "$work/answers.txt" || true
run() {
  local name=$1 n=$2 output=$3
  shift 3
  local status=ok
  rm -f "$output"
  /usr/bin/time -f '%U %S %e %M' -o "$work/time.txt" bash -c 'ulimit -t "$0" && exec "$@"' "$cpu_limit_s" "$@" \
    <"$work/answers.txt" >"$work/log.txt" 2>&1 || status=failed
  grep -q 'Command terminated by signal \(24\|9\)' "$work/time.txt" && status=cpu_limit
  [ "$status" = ok ] && [ ! -s "$output" ] && status=no_output
  read -r user sys wall peak < <(tail -1 "$work/time.txt")
  echo "$name $n $(printf "%.2f" "$(echo "$user + $sys" | bc)") $wall $((peak / 1024)) $status $output" >> "$results"
}
for n in $sizes; do
  x=$work/inputs/target_$n.txt y=$work/inputs/source_$n.txt o=$work/out
  if [ "$mode" = nonrigid ]; then
    run partreg "$n" "$o/partreg_$n.ply" "$partreg" cpd "$work/inputs/source_$n.xyz" "$work/inputs/target_$n.xyz" \
      --mode nonrigid --beta 2 --lambda 2 --w 0.1 --tolerance 1e-5 --max-iterations 150 --out "$o/partreg_$n.ply"
    [ -x "$work/build/bcpd" ] && run "BCPD-A" "$n" "$o/bcpdA_${n}_y.txt" "$work/build/bcpd" -x "$x" -y "$y" \
      -w0.1 -b2 -l2 -c1e-5 -n150 -A -sy -o "$o/bcpdA_${n}_"
    [ -x "$work/build/bcpd" ] && run BCPD "$n" "$o/bcpd_${n}_y.txt" "$work/build/bcpd" -x "$x" -y "$y" \
      -w0.1 -b2 -l2 -c1e-5 -n150 -sy -o "$o/bcpd_${n}_"
  else
    run partreg "$n" "$o/partreg_$n.ply" "$partreg" cpd "$work/inputs/source_$n.xyz" "$work/inputs/target_$n.xyz" \
      --mode rigid --w 0.1 --tolerance 1e-6 --max-iterations 150 --out "$o/partreg_$n.ply"
    [ -x "$work/build/bcpd" ] && run "BCPD-A" "$n" "$o/bcpdA_${n}_y.txt" "$work/build/bcpd" -x "$x" -y "$y" \
      -w0.1 -l1e9 -b2 -c1e-6 -n150 -A -sy -o "$o/bcpdA_${n}_"
    [ -x "$work/build/bcpd" ] && run BCPD "$n" "$o/bcpd_${n}_y.txt" "$work/build/bcpd" -x "$x" -y "$y" \
      -w0.1 -l1e9 -b2 -c1e-6 -n150 -sy -o "$o/bcpd_${n}_"
  fi
  [ -x "$work/build/gadomski_cpd" ] && run gadomski/cpd "$n" "$o/gadomski_$n.txt" \
    "$work/build/gadomski_cpd" "$mode" "$x" "$y" "$o/gadomski_$n.txt"
  [ -n "$pycpd_src" ] && run pycpd "$n" "$o/pycpd_$n.txt" env PYTHONPATH="$pycpd_src" "$python" -c "
import numpy as np, sys
from pycpd import DeformableRegistration, RigidRegistration
X, Y = np.loadtxt('$x'), np.loadtxt('$y')
if '$mode' == 'rigid': reg = RigidRegistration(X=X, Y=Y, w=0.1, tolerance=1e-6, max_iterations=150)
else: reg = DeformableRegistration(X=X, Y=Y, alpha=2.0, beta=2.0, w=0.1, tolerance=1e-5, max_iterations=150)
np.savetxt('$o/pycpd_$n.txt', reg.register()[0])"
done

# --- the table ---
"$python" - "$results" "$work/inputs" "$mode" <<'PY'
import sys, numpy as np
results, inputs, mode = sys.argv[1], sys.argv[2], sys.argv[3]
def nearest_distances(target, moved):
    try:
        from scipy.spatial import cKDTree
        return cKDTree(target).query(moved)[0]
    except ImportError:  # without python3-scipy: blocks of all pairs
        return np.concatenate([np.sqrt(((block[:, None, :] - target[None]) ** 2).sum(-1).min(1))
                               for block in np.array_split(moved, max(1, len(moved) // 256))])
def read_moved(path):
    if path.endswith('.ply'):
        lines = open(path, 'rb').read().decode('latin-1').splitlines()
        count = int(next(l for l in lines if l.startswith('element vertex')).split()[2])
        if any(l.startswith('format ascii') for l in lines):
            start = lines.index('end_header') + 1
            return np.array([[float(v) for v in l.split()[:3]] for l in lines[start:start + count]])
        raw = open(path, 'rb').read()
        header = raw[:raw.index(b'end_header') + len('end_header') + 1]
        props = [l.split()[1:] for l in header.decode().splitlines() if l.startswith('property')]
        types = {'float': 'f4', 'double': 'f8', 'uchar': 'u1', 'int': 'i4', 'uint': 'u4', 'float32': 'f4', 'float64': 'f8', 'uint8': 'u1', 'int32': 'i4'}
        dtype = np.dtype([(p[1], '<' + types[p[0]]) for p in props if p[0] != 'list'][:], align=False)
        data = np.frombuffer(raw[len(header):], dtype=dtype, count=count)
        return np.stack([data['x'], data['y'], data['z']], 1).astype(float)
    return np.loadtxt(path)
rows = [l.split() for l in open(results) if l.strip()]
print(f'| {mode} | points | CPU s | wall s | peak MB | fit (share of diagonal) | partreg CPU / this |')
print('|---|---|---|---|---|---|---|')
for name, n, cpu, wall, peak, status, out in rows:
    fit = '-'
    if status == 'ok':
        try:
            moved = read_moved(out)
            target = np.loadtxt(f'{inputs}/target_{n}.txt')
            fit = f'{nearest_distances(target, moved).mean():.4f}'
        except Exception as error:
            fit = f'unread ({type(error).__name__})'
    mine = next((float(r[2]) for r in rows if r[0] == 'partreg' and r[1] == n and r[5] == 'ok'), None)
    # CPU seconds print with two decimals: a run under 5 ms shows 0.00 and gets no ratio.
    measurable = status == 'ok' and name != 'partreg' and mine is not None and float(cpu) > 0
    ratio = f'{mine / float(cpu):.3f}' if measurable else ''
    shown_cpu = cpu if status == 'ok' else f'> {cpu} ({status})'
    print(f'| {name} | {n} | {shown_cpu} | {wall} | {peak} | {fit} | {ratio} |')
PY
