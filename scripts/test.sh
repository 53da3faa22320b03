#!/usr/bin/env bash
# Installs what is needed, builds the dev configuration and runs the whole test suite (Vulkan
# validation on; the viewer test starts its own Xvfb), then the sanitizer + fuzzing subset: the
# hostile-input paths (scene, rule, BVH, glTF and joint-limit loaders) built with clang, ASan and
# UBSan as libFuzzer targets, each fuzzed for ALOHA_FUZZ_SECONDS (default 20) from its seed corpus.
# ALOHA_SANITIZERS=1 also builds and runs the whole suite under the asan-ubsan preset (long).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export ALOHA_VALIDATION=1
cmake --preset dev >/dev/null
cmake --build --preset dev
xvfb-run -a ctest --preset dev -j2   # a virtual X server so the window tests run too
bash scripts/fuzz.sh "${ALOHA_FUZZ_SECONDS:-20}"
if [ "${ALOHA_SANITIZERS:-0}" = "1" ]; then
  cmake --preset asan-ubsan >/dev/null
  cmake --build --preset asan-ubsan
  ctest --preset asan-ubsan -j2 -LE "gpu|install|slow|fuzz"
fi
