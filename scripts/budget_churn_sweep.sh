#!/usr/bin/env bash
# Level changes of the separate budget parts against the single total, swept (issue 17): on
# data/scenes/plaza_budget.json at each crowd size, rounds of (the parts, each variant; then the single
# total at each factor x the parts' settled CPU-systems mean of the first round), alternated, each run
# with the load average beside it; then scripts/budget_churn_summary.py interpolates the single total's
# settled level changes a second at each parts run's achieved CPU mean. Run it idle for figures to quote.
#
# Environment (all optional):
#   B        the aloha binary (./build/release/host/tool/aloha)
#   SIZES    crowd sizes ("300 600")
#   ROUNDS   rounds (2)
#   FACTORS  single-total targets as factors of the parts' CPU mean ("0.7 0.85 1.0 1.15 1.3")
#   VARIANTS parts variants, each NAME or NAME:key=value,key=value setting budget keys of a copy of
#            the scene's rule file ("parts"; e.g. "hold0:swap_hold_s=0 hold:swap_hold_s=0.5")
#   FRAMES   measured frames (600), WARMUP (30)
#   OUT      output folder (out/budget_churn)
set -euo pipefail
B=${B:-./build/release/host/tool/aloha}
SIZES=${SIZES:-"300 600"}
ROUNDS=${ROUNDS:-2}
FACTORS=${FACTORS:-"0.7 0.85 1.0 1.15 1.3"}
VARIANTS=${VARIANTS:-parts}
FRAMES=${FRAMES:-600}
WARMUP=${WARMUP:-30}
OUT=${OUT:-out/budget_churn}
SCENE=data/scenes/plaza_budget.json
mkdir -p "$OUT"
here=$(cd "$(dirname "$0")" && pwd)

# A copy of the scene and its rule file with budget keys set (NAME:key=value,...), or the scene itself.
scene_for() {
  local spec=$1 name=${1%%:*} sets=""
  [[ $spec == *:* ]] && sets=${spec#*:}
  if [[ -z $sets ]]; then echo "$SCENE"; return; fi
  local dir="$OUT/scenes/$name"
  mkdir -p "$dir"
  python3 - "$SCENE" "$dir" "$sets" <<'PY'
import json, os, sys
scene, out, sets = sys.argv[1], sys.argv[2], sys.argv[3]
s = json.load(open(scene))
rules = os.path.join(os.path.dirname(scene), s["rules"])
r = json.load(open(rules))
for kv in sets.split(","):
    k, v = kv.split("=")
    r["budget"][k] = json.loads(v)
s.pop("$schema", None)
r.pop("$schema", None)
s["rules"] = "rules.json"
json.dump(r, open(os.path.join(out, "rules.json"), "w"), indent=1)
json.dump(s, open(os.path.join(out, "scene.json"), "w"), indent=1)
PY
  echo "$dir/scene.json"
}

# One profile run into $OUT/runs/<label>; its load average (1 min) before and after into meta.json.
run() {
  local label=$1 scene=$2 n=$3; shift 3
  local dir="$OUT/runs/$label" l0 l1
  l0=$(cut -d' ' -f1 /proc/loadavg)
  "$B" profile "$scene" --no-render --characters "$n" --frames "$FRAMES" --warmup "$WARMUP" --out "$dir" --force --quiet "$@" >/dev/null
  l1=$(cut -d' ' -f1 /proc/loadavg)
  printf '{"label":"%s","characters":%s,"load_before":%s,"load_after":%s,"args":"%s","utc":"%s"}\n' \
    "$label" "$n" "$l0" "$l1" "$*" "$(date -u +%H:%M:%S)" >"$dir/meta.json"
  echo "$(date -u +%H:%M:%S) $label load $l0 -> $l1" >&2
}

for n in $SIZES; do
  T=""
  for r in $(seq 1 "$ROUNDS"); do
    for v in $VARIANTS; do
      run "n${n}_r${r}_${v%%:*}" "$(scene_for "$v")" "$n"
    done
    if [[ -z $T ]]; then  # the first round's parts: mean of their settled CPU means
      T=$(python3 "$here/budget_churn_summary.py" --cpu-mean "$OUT/runs" "n${n}_r1_")
      echo "n=$n: single total around T = $T ms" >&2
    fi
    for f in $FACTORS; do
      t=$(python3 -c "print(round($f * $T, 3))")
      run "n${n}_r${r}_single${f}" "$SCENE" "$n" --budget-single-ms "$t"
    done
  done
done
python3 "$here/budget_churn_summary.py" "$OUT/runs" | tee "$OUT/summary.md"
