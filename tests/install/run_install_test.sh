#!/usr/bin/env bash
# usage: run_install_test.sh BUILD_DIR CONSUMER_SOURCE WORK_DIR
set -euo pipefail
build="$1"; consumer="$2"; work="$3"
rm -rf "$work"
mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" >/dev/null
cmake -S "$consumer" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/build"
"$work/build/mini_game" "$consumer/mini_game.json" "$work/frame.png"
test -s "$work/frame.png"
echo "install_consumer: ok"
