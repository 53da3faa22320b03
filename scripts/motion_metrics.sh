#!/usr/bin/env bash
# Motion quality figures of docs/PERFORMANCE.md: foot skate and pops per animation level and update
# interval (aloha profile --motion-metrics) on the default 1,000 crowd and on a 1,000 crowd walking the
# CMU 131_01 BVH take (read from $ALOHA_TEST_ASSETS, else ../shared/assets; skipped with a message when
# absent). Each crowd runs twice: with the scene's own rules (on a small machine they put a far crowd at
# the clip levels only) and with out/motion/motion_levels.rules.json, the default rules whose rule list
# assigns every animation level by importance band (and one level down at the edge of the view, so
# characters walking across it switch level), so every level and update interval 1, 2, 4, 8 is walked.
# Usage: scripts/motion_metrics.sh [BUILD_DIR] [OUT_DIR]   (defaults build/release, out/motion)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
out=${2:-out/motion}
aloha="$build/host/tool/aloha"
[ -x "$aloha" ] || { echo "motion_metrics.sh: $aloha not built (cmake --preset release && cmake --build build/release)" >&2; exit 1; }
mkdir -p "$out"
frames=600

profile() {  # profile SCENE NAME
  "$aloha" profile "$1" --no-render --motion-metrics --frames "$frames" --quiet --force --out "$out/$2" |
    sed -n '/^motion metrics/,$p'
}

# Rules that populate every animation level: the default knowledge base (levels, hysteresis, costs)
# with its rule list replaced by importance bands; budget off so the assignment is reproducible.
python3 - "$out/motion_levels.rules.json" <<'PY'
import json, sys
r = json.load(open("data/rules/default.json"))
r.pop("$schema", None)
r["description"] = ("scripts/motion_metrics.sh: data/rules/default.json with every animation level assigned by "
                    "importance band (one level down past eccentricity 0.6), so every level and update interval is walked")
r["default_tier"] = "high"
r["budget"]["enabled"] = False
band = lambda lo, hi: {"ge": lo, "lt": hi}
r["rules"] = [
    {"name": "hero", "when": {"importance": band(0.62, 2.0), "eccentricity": {"lt": 0.6}},
     "then": {"geometry": "skinned", "animation": "dynamic_dls"}},
    {"name": "ccd", "when": {"importance": band(0.50, 2.0), "eccentricity": {"lt": 0.6}},
     "then": {"geometry": "skinned", "animation": "kinematic_ccd"}},
    {"name": "cheap", "when": {"importance": band(0.38, 2.0), "eccentricity": {"lt": 0.6}},
     "then": {"geometry": "skinned", "animation": "kinematic_cheap"}},
    {"name": "edge_cheap", "when": {"importance": band(0.50, 2.0)},
     "then": {"geometry": "skinned", "animation": "kinematic_cheap"}},
    {"name": "clip", "when": {"importance": band(0.25, 2.0)},
     "then": {"geometry": "proxy", "animation": "clip"}},
    {"name": "sparse", "then": {"geometry": "proxy", "animation": "clip_sparse"}},
]
json.dump(r, open(sys.argv[1], "w"), indent=2)
PY
python3 - "$out/crowd_1k_levels.json" <<'PY'
import json, sys
s = json.load(open("data/scenes/crowd_1k.json"))
s.pop("$schema", None)
s["name"] = "crowd_1k_levels"
s["rules"] = "motion_levels.rules.json"
json.dump(s, open(sys.argv[1], "w"), indent=2)
PY

echo "== crowd_1k (built-in humanoid, generated motion library), the scene's rules"
profile data/scenes/crowd_1k.json crowd_1k
echo "== crowd_1k, every level populated (motion_levels.rules.json)"
profile "$out/crowd_1k_levels.json" crowd_1k_levels

assets=${ALOHA_TEST_ASSETS:-../shared/assets}
bvh="$(realpath -m "$assets/131_01.bvh")"
if [ ! -f "$bvh" ]; then
  echo "== cmu_131_01: skipped: $bvh not found (set ALOHA_TEST_ASSETS to the folder holding 131_01.bvh)"
  exit 0
fi
# The same crowd, every character a CMU skeleton walking (the take's loop, or the kinematic walk when
# the take cannot be looped: see docs/MOTION.md 'Loops cut from files').
# Scene files may only name files inside their folder: the take is copied beside the scene (out/ is
# not part of the repository).
scene="$out/cmu_131_01.json"
cp "$bvh" "$out/131_01.bvh"
python3 - "$scene" <<'PY'
import json, sys
s = json.load(open("data/scenes/crowd_1k.json"))
s["name"] = "cmu_131_01_1k"
s.pop("$schema", None)
s["character_types"] = [{"name": "cmu", "bvh": "131_01.bvh"}]  # mapped to the humanoid: muscles, limits, walk
c = s["crowds"][0]
for key in ("height", "build", "variants"):
    c.pop(key, None)
c.update({"type": "cmu", "mix": {"walk": 1.0}})
json.dump(s, open(sys.argv[1], "w"), indent=2)
s["name"] = "cmu_131_01_1k_levels"
s["rules"] = "motion_levels.rules.json"
json.dump(s, open(sys.argv[1].replace(".json", "_levels.json"), "w"), indent=2)
PY
echo "== cmu_131_01 ($bvh), the scene's rules"
profile "$scene" cmu_131_01
echo "== cmu_131_01, every level populated (motion_levels.rules.json)"
profile "${scene%.json}_levels.json" cmu_131_01_levels
