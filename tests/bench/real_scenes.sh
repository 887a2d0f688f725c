#!/usr/bin/env bash
# Real scenes at each quality (issue 32's benchmark): for every scene, `radiosity solve` at the
# qualities asked, one process each, measured by GNU time (wall seconds, peak resident MiB), with
# the true error against a path-traced reference (`radiosity reference`, independent of the
# hemicubes) from the solve's report. One CSV row per run; plot with real_scenes_plot.py.
#
#   tests/bench/real_scenes.sh BUILD OUT_DIR [--quality Q,Q,...] [--time-limit S] [SCENE.json ...]
#
# Without scenes: the shipped Cornell box, CornellBox-Original and doorway (their committed
# references in tests/data/references/), and the Bitterli interiors in ../shared/scenes/bitterli
# when at hand (references made once into OUT_DIR/references/, 300 points, kept for later runs).
# Any other scene (a downloaded model wrapped in a one-line scene file) gets its reference the
# same way. --time-limit passes the solve's limit (a run past it is marked in the CSV's `stop`).
set -euo pipefail
build=$1 out=$2
shift 2
qualities=draft,default
limit=""
while [ $# -gt 0 ]; do
  case $1 in
    --quality) qualities=$2; shift 2 ;;
    --time-limit) limit="--time-limit $2"; shift 2 ;;
    *) break ;;
  esac
done
here=$(cd "$(dirname "$0")/../.." && pwd)
radiosity=$build/bin/radiosity
[ -x "$radiosity" ] || { echo "real_scenes.sh: $radiosity not built (cmake --build $build --target radiosity_cli)" >&2; exit 1; }
command -v /usr/bin/time > /dev/null || { echo "real_scenes.sh: GNU time (/usr/bin/time) is needed: apt-get install time" >&2; exit 1; }
mkdir -p "$out/references" "$out/runs"

scenes=("$@")
if [ ${#scenes[@]} -eq 0 ]; then
  scenes=("$here/scenes/cornell.json" "$here/scenes/cornell_original.json" "$here/scenes/doorway.json")
  for s in staircase2 living-room staircase; do
    f=$here/../shared/scenes/bitterli/$s/scene.json
    [ -f "$f" ] && scenes+=("$f")
  done
fi

# The scene's short name: its file's, or its folder's for a scene.json.
name_of() {
  local base
  base=$(basename "$1" .json)
  [ "$base" = scene ] && base=$(basename "$(dirname "$1")")
  echo "$base"
}

# The reference for a scene: the committed one, else one made (and kept) in OUT_DIR.
reference_of() {
  local name=$1 scene=$2 committed=$here/tests/data/references/${1}_reference.csv
  if [ -f "$committed" ]; then echo "$committed"; return; fi
  local made=$out/references/$name.csv
  if [ ! -f "$made" ]; then
    echo "real_scenes.sh: path tracing a reference for $name (300 points)" >&2
    "$radiosity" reference "$scene" -o "$made" --count 300 > /dev/null 2> "$out/references/$name.log"
  fi
  echo "$made"
}

csv=$out/real_scenes.csv
echo "scene,quality,elements,vertices,gather_points,seconds,peak_mib,rms_percent,worst_percent,stop" > "$csv.tmp"
IFS=, read -r -a qs <<< "$qualities"
for scene in "${scenes[@]}"; do
  name=$(name_of "$scene")
  ref=$(reference_of "$name" "$scene")
  for q in "${qs[@]}"; do
    run=$out/runs/$name.$q
    echo "real_scenes.sh: $name at $q" >&2
    status=0
    # shellcheck disable=SC2086  # $limit is two words or none
    /usr/bin/time -f "%e %M" -o "$run.time" "$radiosity" solve "$scene" -o "$run.ply" --report "$run.json" \
      --reference "$ref" --quality "$q" $limit > "$run.log" 2>&1 || status=$?
    if [ $status -ne 0 ]; then
      echo "$name,$q,,,,,,,,failed ($status; see $run.log)" >> "$csv.tmp"
      continue
    fi
    read -r seconds kib < <(tail -1 "$run.time")
    python3 - "$run.json" "$name" "$q" "$seconds" "$kib" >> "$csv.tmp" <<'EOF'
import json, sys
report, name, quality, seconds, kib = sys.argv[1:]
r = json.load(open(report))
error = r.get("error", {})
worst = error.get("worst", {}).get("relative_error")
gather = r.get("final_gather") or {}
print(",".join(str(x) for x in [
    name, quality, r["counts"]["elements"], r["counts"]["vertices"], gather.get("points", 0), seconds,
    round(float(kib) / 1024), round(100 * error["rms"], 2) if "rms" in error else "",
    round(100 * worst, 1) if worst is not None else "", r.get("stop_reason", "")]))
EOF
  done
done
mv "$csv.tmp" "$csv"
column -s, -t "$csv"
