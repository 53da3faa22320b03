#!/usr/bin/env bash
# usage: run_install_test.sh BUILD_DIR CONSUMER_SOURCE WORK_DIR
set -euo pipefail
build="$1"; consumer="$2"; work="$3"
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
# No source-tree data path is baked into the installed libraries: they find their data through the
# package (ALOHA_DATA_DIR from alohaConfig.cmake), never through this checkout.
source_data="$(cd "$consumer/../../.." && pwd)/data"
if grep -rlaF "$source_data" "$work/prefix/lib"; then
  echo "install_consumer: an installed library names the source tree's $source_data" >&2; exit 1
fi
unset ALOHA_DATA_DIR
cmake -S "$consumer" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build"
"$work/build/mini_game" "$consumer/mini_game.json" "$work/frame.png"
test -s "$work/frame.png"
echo "install_consumer: ok"
