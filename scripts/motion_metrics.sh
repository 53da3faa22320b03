#!/usr/bin/env bash
# Motion quality figures of docs/PERFORMANCE.md: foot skate and pops per animation level and update
# interval (aloha profile --motion-metrics) on the default 1,000 crowd and on a 1,000 crowd walking the
# CMU 131_01 BVH take (read from $ALOHA_TEST_ASSETS, else ../shared/assets; skipped with a message when
# absent). Usage: scripts/motion_metrics.sh [BUILD_DIR] [OUT_DIR]   (defaults build/release, out/motion)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build/release}
out=${2:-out/motion}
aloha="$build/engine/tool/aloha"
[ -x "$aloha" ] || { echo "motion_metrics.sh: $aloha not built (cmake --preset release && cmake --build build/release)" >&2; exit 1; }
mkdir -p "$out"
frames=600

echo "== crowd_1k (built-in humanoid, generated motion library)"
"$aloha" profile data/scenes/crowd_1k.json --no-render --motion-metrics --frames "$frames" --quiet --force --out "$out/crowd_1k" |
  sed -n '/^motion metrics/,$p'

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
PY
echo "== cmu_131_01 ($bvh)"
"$aloha" profile "$scene" --no-render --motion-metrics --frames "$frames" --quiet --force --out "$out/cmu_131_01" |
  sed -n '/^motion metrics/,$p'
