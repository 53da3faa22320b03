#!/usr/bin/env bash
# The main job: install what is needed, build the release tool, profile the default scene headless
# (lavapipe, no window) and write the report, trace, CSV, plot and a PNG of the last frame to out/profile.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset release >/dev/null
cmake --build --preset release --target aloha_tool
SCENE="${1:-data/scenes/crowd_1k.json}"
OUT="${OUT:-out/profile}"
# --force: this script owns out/profile and refreshes it on every run.
./build/release/host/tool/aloha profile "$SCENE" --out "$OUT" --force "${@:2}"
echo "main: report in $OUT/report.json, picture in $OUT/last_frame.png"
