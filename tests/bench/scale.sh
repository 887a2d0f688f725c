#!/usr/bin/env bash
# Cost against size (bench_scale): the interior split to each size, one process per size, every
# stage's time and the peak memory once it is done, into one CSV. With --solve, the solve too.
#   tests/bench/scale.sh BUILD OUT.csv [--solve] [SIZES...]
set -euo pipefail
build=$1 out=$2
shift 2
solve=""
if [ "${1:-}" = "--solve" ]; then solve="--solve"; shift; fi
sizes=("$@")
[ ${#sizes[@]} -gt 0 ] || sizes=(30000 100000 300000 1000000)
echo "triangles,elements,vertices,stage,seconds,peak_mib" > "$out.tmp"
for n in "${sizes[@]}"; do
  "$build/bin/bench_scale" "$n" $solve | tee -a "$out.tmp"
done
mv "$out.tmp" "$out"
