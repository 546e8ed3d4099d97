#!/usr/bin/env bash
# MPI speed-ups (docs/cluster.md, docs/performance.md): the same work on
# 1 rank × 1 thread and on N ranks × 1 thread each, wall time and speed-up:
#   1. the demo's frames (examples/demo/scene.json, 160×80 px, with the photon
#      map it used until 2026-12-07),
#      shared by frames: --time 0:30:6 (6 frames);
#   2. one 512×256 frame of the demo's four sensors (radiance cache, t = 8 s),
#      shared by tiles: rows and photon chunks;
#   3. the salvo study (examples/salvo-study, 16 cases) with its scene at the
#      quick demo's 64×32 px, shared by cases.
# The tables of 1 and N ranks must be the same bytes (time_series.csv,
# metrics.csv; the study's results.csv but for its wall times), else it stops.
#   bench/bench_mpi.sh [RANKS [WORK...]]
# RANKS defaults to 2 (needs a build with MPI); WORK is any of frames, tiles
# and study (default all three). On a shared machine wall times wander by
# 20 % between runs: REPEAT=K runs each piece K times as interleaved pairs
# (1 rank, then N ranks) and reports every pair and the median speed-up.
set -euo pipefail
cd "$(dirname "$0")/.."
OBSCURA=${OBSCURA:-$PWD/build/release/apps/obscura/obscura}
RANKS=${1:-2}
shift $(($# > 0 ? 1 : 0))
PIECES=${*:-frames tiles study}
REPEAT=${REPEAT:-1}
for piece in $PIECES; do
  case $piece in frames | tiles | study) ;; *) echo "bench_mpi: unknown work '$piece' (frames, tiles or study)" >&2; exit 2 ;; esac
done
wants() { [[ " $PIECES " == *" $1 "* ]]; }
MPIRUN=${MPIRUN:-mpirun --allow-run-as-root --oversubscribe}
WORK=$(mktemp -d /tmp/obscura-bench-mpi.XXXXXX)
trap 'rm -rf "$WORK"' EXIT

# Wall time of a command in seconds; its output is dropped (a failure shows it).
seconds() {
  local t0=$EPOCHREALTIME status=0
  "$@" >"$WORK/stdout" 2>"$WORK/stderr" || status=$?
  # study exits 3 when some cases failed; none should here.
  if [ "$status" -ne 0 ]; then cat "$WORK/stderr" >&2; exit 1; fi
  awk -v a="$t0" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }'
}
report() {
  awk -v what="$1" -v a="$2" -v b="$3" -v n="$RANKS" 'BEGIN {
    printf "%-46s 1 rank %7.2f s   %d ranks %7.2f s   speed-up %.2f\n", what, a, n, b, a / b }'
  echo "$2 $3" >>"$WORK/pairs"
}
# After REPEAT > 1 pairs of one piece: the median of their speed-ups.
median() {
  if [ "$REPEAT" -gt 1 ]; then
    awk '{ print $1 / $2 }' "$WORK/pairs" | sort -g |
      awk -v what="$1" '{ v[NR] = $1 } END {
        m = NR % 2 ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2
        printf "%-46s median speed-up %.2f of %d pairs (%.2f to %.2f)\n", what, m, NR, v[1], v[NR] }'
  fi
  rm -f "$WORK/pairs"
}
same() { for f in "$@"; do cmp -s "$WORK/one/$f" "$WORK/many/$f" || { echo "bench_mpi: $f differs between 1 and $RANKS ranks" >&2; exit 1; }; done; }

echo "bench_mpi: $(nproc) cores, $RANKS ranks × 1 thread against 1 × 1"
"$OBSCURA" prepare examples/smoke-screen/prepare.json -o "$WORK/cloud" -q >/dev/null
cp examples/tank/tank.obj "$WORK/"
cp examples/demo/scene.json "$WORK/demo.json"
python3 - "$WORK" <<'PY'
import json, sys
w = sys.argv[1]
demo = json.load(open(f"{w}/demo.json"))
# The demo as these figures were first measured (docs/performance.md): its
# frames with the photon map as the demo then used (the demo has used the
# radiance cache since 2026-12-07), the large frame with the cache's defaults.
render = {k: v for k, v in demo["render"].items()
          if k not in ("method", "radiance_cache", "samples_per_pixel", "adaptive_threshold")}
s = dict(demo, render=dict(render, method="photonmap", photon_map={"photons": 200000, "k": 30}))
json.dump(s, open(f"{w}/demo.json", "w"))
s = dict(demo, render=dict(render, method="radiance-cache"))
for sensor in s["sensors"]:
    sensor["width"], sensor["height"] = 512, 256
for r in s.get("regions", []):
    r["pixels"] = [p * 512 // 160 for p in r["pixels"]]
json.dump(s, open(f"{w}/big.json", "w"))
PY

if wants frames; then
  for _ in $(seq "$REPEAT"); do
    rm -rf "$WORK/one" "$WORK/many"
    a=$(seconds "$OBSCURA" render "$WORK/demo.json" -o "$WORK/one" --time 0:30:6 --threads 1)
    b=$(seconds $MPIRUN -np "$RANKS" "$OBSCURA" render "$WORK/demo.json" -o "$WORK/many" --time 0:30:6 --threads 1)
    same time_series.csv metrics.csv
    report "demo frames (6 × 4 sensors 160×80, by frames)" "$a" "$b"
  done
  median "demo frames"
fi

if wants tiles; then
  for _ in $(seq "$REPEAT"); do
    rm -rf "$WORK/one" "$WORK/many"
    a=$(seconds "$OBSCURA" render "$WORK/big.json" -o "$WORK/one" --at 8 --threads 1)
    b=$(seconds $MPIRUN -np "$RANKS" "$OBSCURA" render "$WORK/big.json" -o "$WORK/many" --at 8 --threads 1)
    same metrics.csv
    report "one frame (4 sensors 512×256, by tiles)" "$a" "$b"
  done
  median "one frame by tiles"
fi

wants study || exit 0
mkdir -p "$WORK/study"
cp examples/salvo-study/study.json "$WORK/study/"
python3 - "$WORK" "$PWD" <<'PY'
import json, sys
w, root = sys.argv[1], sys.argv[2]
s = json.load(open(f"{root}/examples/salvo-study/scene.json"))
s["sensors"][0]["width"], s["sensors"][0]["height"] = 64, 32
s.pop("regions", None)
json.dump(s, open(f"{w}/study/scene.json", "w"))
st = json.load(open(f"{w}/study/study.json"))
st["prepare"] = f"{root}/examples/smoke-screen/prepare.json"
json.dump(st, open(f"{w}/study/study.json", "w"))
PY
for _ in $(seq "$REPEAT"); do
  rm -rf "$WORK/study-one" "$WORK/study-many"
  a=$(seconds "$OBSCURA" study "$WORK/study/study.json" -o "$WORK/study-one" --threads 1)
  b=$(seconds $MPIRUN -np "$RANKS" "$OBSCURA" study "$WORK/study/study.json" -o "$WORK/study-many" --threads 1)
  cut -d, -f1-5,7- "$WORK/study-one/results.csv" >"$WORK/a.csv"
  cut -d, -f1-5,7- "$WORK/study-many/results.csv" >"$WORK/b.csv"
  cmp -s "$WORK/a.csv" "$WORK/b.csv" || { echo "bench_mpi: the study tables differ" >&2; exit 1; }
  report "salvo study (16 cases, 64×32 px, by cases)" "$a" "$b"
done
median "salvo study"
