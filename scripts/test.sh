#!/usr/bin/env bash
# Installs what is needed, builds the dev configuration and runs the whole test suite
# (Vulkan validation on; the viewer test runs under Xvfb). Set ALOHA_SANITIZERS=1 to also run the
# ASan+UBSan configuration over the labelled subset (see README).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export ALOHA_VALIDATION=1
cmake --preset dev >/dev/null
cmake --build --preset dev
ctest --preset dev -j2
if [ "${ALOHA_SANITIZERS:-0}" = "1" ]; then
  cmake --preset asan-ubsan >/dev/null
  cmake --build --preset asan-ubsan
  ctest --preset asan-ubsan -j2 -LE "slow|gpu"
fi
