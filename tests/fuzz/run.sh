#!/usr/bin/env bash
# Runs the fuzz targets (all, or those named) for SECONDS each (default 60), seeded with the
# project's own files; crashes, leaks and hangs are saved under BUILD/crashes/TARGET/ and make
# the run fail.
#   tests/fuzz/run.sh BUILD [SECONDS [TARGET...]]
set -euo pipefail
build=${1:?usage: run.sh BUILD [SECONDS [TARGET...]]}
seconds=${2:-60}
shift $(( $# < 2 ? $# : 2 ))
targets=(scene obj ply off gltf result reference)
[ $# -eq 0 ] || targets=("$@")
root=$(cd "$(dirname "$0")/../.." && pwd)
declare -A seeds=(
  [scene]="$root/scenes/*.json $root/scenes/stress/*.json $root/tests/data/*.json $root/tests/data/bad/*.json"
  [obj]="$root/tests/data/*.obj $root/tests/data/bad/*.obj"
  [ply]="$root/tests/data/*.ply $root/tests/data/bad/ply_*.ply"
  [off]="$root/tests/data/*.off $root/tests/data/bad/*.off"
  [gltf]="$root/tests/data/*.gltf $root/tests/data/*.glb"
  [result]="$root/tests/data/*.ply $root/tests/data/bad/result_*.ply"
  [reference]="$root/tests/data/references/cornell_reference.csv $root/tests/data/bad/bad_reference.csv"
)
failed=0
for target in "${targets[@]}"; do
  corpus=$build/corpus/$target crashes=$build/crashes/$target
  mkdir -p "$corpus" "$crashes"
  # shellcheck disable=SC2086
  cp ${seeds[$target]} "$corpus"/ 2>/dev/null || true
  log=$build/fuzz_$target.log
  if "$build/fuzz_$target" "$corpus" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
       -max_len=65536 -artifact_prefix="$crashes/" -print_final_stats=1 > "$log" 2>&1; then
    status=ok
  else
    status=FAILED
    failed=1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo "?")
  cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*' || echo "?")
  echo "fuzz_$target: $status, $runs executions in ${seconds} s, coverage $cov edges, corpus $(ls "$corpus" | wc -l) inputs"
  [ "$status" = ok ] || tail -40 "$log"
done
exit $failed
