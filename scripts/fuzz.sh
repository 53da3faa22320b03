#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan) and runs each for N seconds, JOBS (default 2) at a time.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET=60] [TARGET...]
#   Targets: fuzz_scene fuzz_rules fuzz_bvh fuzz_gltf fuzz_joint_limits (default: all).
#   BUILD_DIR (default build-fuzz) sets the build folder; WORK_DIR (default $BUILD_DIR/fuzz-work)
#   receives the grown corpora (the seed corpora in tests/fuzz/corpus/ are only read), crash files and logs.
#   KEEP_GOING=1 runs libFuzzer in fork mode and keeps fuzzing after crashes, timeouts and OOMs (all
#   are saved under $WORK_DIR/<target>/crashes); default: stop at the first one.
# Prints, per target: executions, exec/s, coverage (cov:) and features (ft:) at the end, and any crash.
# Exit status 1 when a target crashed, leaked, timed out or ran out of memory.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SECONDS_PER_TARGET=${1:-60}
shift || true
TARGETS=("$@")
[ ${#TARGETS[@]} -eq 0 ] && TARGETS=(fuzz_scene fuzz_rules fuzz_bvh fuzz_gltf fuzz_joint_limits)
BUILD_DIR=${BUILD_DIR:-$ROOT/build-fuzz}
WORK_DIR=${WORK_DIR:-$BUILD_DIR/fuzz-work}
FLAGS="-fsanitize=address,undefined -fsanitize=fuzzer-no-link -fno-sanitize-recover=all -gline-tables-only -O1"

if [ ! -f "$BUILD_DIR/CMakeCache.txt" ]; then
  cmake -S "$ROOT/tests/fuzz" -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
        -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_C_FLAGS="$FLAGS" \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-DNDEBUG" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-DNDEBUG" >/dev/null
fi
cmake --build "$BUILD_DIR" --target "${TARGETS[@]}" -j"${JOBS:-2}"

dict_of() {
  case "$1" in
    fuzz_scene) echo scene.dict ;; fuzz_rules) echo rules.dict ;; fuzz_bvh) echo bvh.dict ;;
    fuzz_gltf) echo gltf.dict ;; fuzz_joint_limits) echo limits.dict ;;
  esac
}

# One target = one process on one core: JOBS (default 2) targets fuzz at a time, results printed in order.
run_target() {
  local t=$1 exe corpus crashes log args dict result execs speed last crashed cov ft
  exe=$(find "$BUILD_DIR" -maxdepth 3 -type f -name "$t" -perm -u+x | head -n1)
  [ -n "$exe" ] || { echo "$t: executable not found under $BUILD_DIR" >&2; return 1; }
  corpus="$WORK_DIR/$t/corpus"; crashes="$WORK_DIR/$t/crashes"; log="$WORK_DIR/$t/fuzz.log"
  mkdir -p "$corpus" "$crashes"
  args=(-max_total_time="$SECONDS_PER_TARGET" -rss_limit_mb=2048 -timeout=10 -print_final_stats=1
        -artifact_prefix="$crashes/" "$corpus" "$ROOT/tests/fuzz/corpus/$t")
  [ "${KEEP_GOING:-0}" = 1 ] && args=(-fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 "${args[@]}")
  dict=$(dict_of "$t")
  [ -n "$dict" ] && [ -f "$ROOT/tests/fuzz/$dict" ] && args=(-dict="$ROOT/tests/fuzz/$dict" "${args[@]}")
  result=ok
  ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1} "$exe" "${args[@]}" >"$log" 2>&1 || result="FAILED (see $log and $crashes)"
  execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  speed=$(grep -o 'stat::average_exec_per_sec: *[0-9]*' "$log" | grep -o '[0-9]*$' || true)
  last=$(grep -E '^#[0-9]+' "$log" | grep 'cov:' | tail -n1 || true)
  [ -n "$execs" ] || execs=$(echo "$last" | grep -oE '^#[0-9]+' | tr -d '#' || true)
  crashed=$(find "$crashes" -type f | wc -l)
  [ "$crashed" -eq 0 ] || result="$crashed crash/timeout/oom file(s) in $crashes"
  cov=$(echo "$last" | grep -o 'cov: [0-9]*' | grep -o '[0-9]*' || true)
  ft=$(echo "$last" | grep -o 'ft: [0-9]*' | grep -o '[0-9]*' || true)
  printf '%-18s %10s %8s %8s %8s %s\n' "$t" "${execs:-?}" "${speed:-?}" "${cov:-?}" "${ft:-?}" "$result" \
    >"$WORK_DIR/$t/result"
  [ "$result" = ok ]
}

status=0
for t in "${TARGETS[@]}"; do
  mkdir -p "$WORK_DIR/$t"
  rm -f "$WORK_DIR/$t/result"
  while [ "$(jobs -rp | wc -l)" -ge "${JOBS:-2}" ]; do wait -n || true; done
  run_target "$t" &
done
wait
printf '%-18s %10s %8s %8s %8s %s\n' target execs exec/s cov ft result
for t in "${TARGETS[@]}"; do
  if [ -f "$WORK_DIR/$t/result" ]; then cat "$WORK_DIR/$t/result"; else echo "$t: no result"; status=1; continue; fi
  [ "$(awk '{print $NF}' "$WORK_DIR/$t/result")" = ok ] || status=1
done
exit $status
