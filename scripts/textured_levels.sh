#!/usr/bin/env bash
# Renders the built-in humanoid of data/scenes/closeup.json with its generated texture (skin, shirt,
# trousers, shoes; systems/geometry/controller/body_texture.hpp) at each mesh level of the default
# rules (the proxy level draws boxes, not the mesh), into docs/images/textured_<level>.png. Each picture uses a copy of the default rules whose only
# rule puts every character at that level (written to a temporary folder, never committed).
# Usage: scripts/textured_levels.sh [path/to/aloha] (default build/dev/host/tool/aloha).
set -euo pipefail
cd "$(dirname "$0")/.."
aloha="${1:-build/dev/host/tool/aloha}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
for level in skinned layered_low layered_high subdivided; do
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
scene["viewport"] = {"width": 560, "height": 720}
scene["camera"] = {"position": [2.0, 1.4, 3.6], "target": [0.0, 0.9, 0.9], "fov_deg": 38}
json.dump(scene, open(f"{tmp}/{level}.json", "w"), indent=1)
PY
  "$aloha" render "$tmp/$level.json" --frame 60 --out "docs/images/textured_$level.png" --force
done
