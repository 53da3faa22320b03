#!/usr/bin/env bash
# Renders the built-in humanoid of data/scenes/closeup.json (generated skin and texture; nothing
# third-party) at every drawn geometric level of the default rules into docs/images/closeup_<level>.png,
# plus docs/images/closeup_overlay.png (bones, muscles and fat springs over layered_low). Each picture uses
# a copy of the default rules whose only rule puts every character at that level, and a camera aimed at
# where the character is at that frame: the character's joints at the frame are exported first
# (`aloha export --joints`), and the camera looks at their centre from in front and to the side, far enough
# for the whole body to fit. Temporary files go to a temporary folder, never committed.
# Usage: scripts/level_pictures.sh [path/to/aloha] (default build/dev/host/tool/aloha).
set -euo pipefail
cd "$(dirname "$0")/.."
aloha="${1:-build/dev/host/tool/aloha}"
frame=60
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
picture() {  # picture LEVEL OUT [render options...]
  local level="$1" out="$2"
  shift 2
  python3 - "$level" "$tmp" <<'PY'
import json, sys
level, tmp = sys.argv[1], sys.argv[2]
rules = json.load(open("data/rules/default.json"))
rules.pop("$schema", None)
rules["rules"] = [{"name": "only_" + level, "when": {}, "then": {"geometry": level, "animation": "kinematic_ccd"}}]
json.dump(rules, open(f"{tmp}/{level}.rules.json", "w"), indent=1)
scene = json.load(open("data/scenes/closeup.json"))
scene.pop("$schema", None)
scene["rules"] = f"{level}.rules.json"  # relative to the scene's folder
json.dump(scene, open(f"{tmp}/{level}.json", "w"), indent=1)
PY
  "$aloha" export "$tmp/$level.json" --joints "$tmp/$level.csv" --characters 0 --frames "$((frame - 10)):$((frame + 1))" --force >/dev/null
  python3 - "$tmp/$level.json" "$tmp/$level.csv" "$frame" <<'PY'
import csv, json, math, sys
scene_path, csv_path, frame = sys.argv[1], sys.argv[2], int(sys.argv[3])
rows = list(csv.DictReader(open(csv_path)))
def joints(f):
    return [(float(r["x"]), float(r["y"]), float(r["z"])) for r in rows if int(r["frame"]) == f]
now, before = joints(frame), joints(frame - 10)
lo = [min(p[i] for p in now) for i in range(3)]
hi = [max(p[i] for p in now) for i in range(3)]
centre = [(lo[i] + hi[i]) / 2 for i in range(3)]
centre[1] = (lo[1] + hi[1]) / 2 - 0.02 * (hi[1] - lo[1])
# Walking direction from the joints' mean motion over the last 10 frames (the +z axis when standing).
mean = lambda ps, i: sum(p[i] for p in ps) / len(ps)
dx, dz = mean(now, 0) - mean(before, 0), mean(now, 2) - mean(before, 2)
heading = math.atan2(dx, dz) if dx * dx + dz * dz > 1e-6 else 0.0
# In front and 35 degrees to the side, slightly above; the whole joint box (plus the head and soles
# beyond the joints, 0.25 m) inside the vertical field of view with a margin.
fov = 36.0
height = hi[1] - lo[1] + 0.25
dist = 1.25 * (height / 2) / math.tan(math.radians(fov / 2))
a = heading + math.radians(35)
eye = [centre[0] + dist * math.sin(a), centre[1] + 0.075 * dist, centre[2] + dist * math.cos(a)]  # ~4 degrees above
scene = json.load(open(scene_path))
scene["viewport"] = {"width": 480, "height": 640}
scene["camera"] = {"position": eye, "target": centre, "fov_deg": fov}
json.dump(scene, open(scene_path, "w"), indent=1)
PY
  "$aloha" render "$tmp/$level.json" --frame "$frame" --out "$out" --force "$@"
}
for level in proxy impostor skinned layered_low layered_high subdivided; do
  picture "$level" "docs/images/closeup_$level.png"
done
picture layered_low docs/images/closeup_overlay.png --overlay bones,muscles,springs
