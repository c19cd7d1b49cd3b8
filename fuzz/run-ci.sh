#!/usr/bin/env bash
# CI fuzzing: build every target with libFuzzer (the `fuzz` preset) and run
# each for a fixed time, two at a time. New inputs go to a temporary
# directory, never into the checked-in corpus. Fails on any crash, leak,
# timeout (-timeout=10) or out-of-memory (-rss_limit_mb=2048). Prints one
# summary line per target. Skips, with a message, when clang++ or libFuzzer
# is missing.
#
#   fuzz/run-ci.sh                   # every target, 60 s each (less when
#                                    # they would not fit TOPKIT_FUZZ_BUDGET=450 s)
#   TOPKIT_FUZZ_SECONDS=10 TOPKIT_FUZZ_JOBS=1 fuzz/run-ci.sh fuzz_frame
#
# Crash inputs are kept under build/fuzz/artifacts/<target>/ (turn each
# into a named regression under fuzz/regressions/<target>/, see README.md).
set -euo pipefail
cd "$(dirname "$0")/.."

seconds=${TOPKIT_FUZZ_SECONDS:-60}
jobs=${TOPKIT_FUZZ_JOBS:-2}
# The whole script (build included) should end within this many seconds:
# when there are too many targets for $seconds each, each gets less.
budget=${TOPKIT_FUZZ_BUDGET:-450}

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz/run-ci.sh: SKIPPED: clang++ not found (install clang and libclang-rt-14-dev to fuzz)"
  exit 0
fi
probe=$(mktemp -d)
trap 'rm -rf "$probe"' EXIT
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' \
  > "$probe/probe.cpp"
if ! clang++ -fsanitize=fuzzer "$probe/probe.cpp" -o "$probe/probe" >/dev/null 2>&1; then
  echo "fuzz/run-ci.sh: SKIPPED: clang++ cannot link -fsanitize=fuzzer (libFuzzer runtime missing: libclang-rt-14-dev)"
  exit 0
fi

started=$(date +%s)
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz --target topkit_fuzz_all
build=build/fuzz/fuzz
dict=$build/top.dict
artifacts=build/fuzz/artifacts
rm -rf "$artifacts"

if [ $# -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(find "$build" -maxdepth 1 -type f -name 'fuzz_*' -perm -u+x -printf '%f\n' | sort)
fi
if [ ${#targets[@]} -eq 0 ]; then
  echo "fuzz/run-ci.sh: no fuzz targets were built" >&2
  exit 1
fi

elapsed=$(( $(date +%s) - started ))
rounds=$(( (${#targets[@]} + jobs - 1) / jobs ))
fair=$(( (budget - elapsed) / rounds ))
if [ "$fair" -lt "$seconds" ]; then
  [ "$fair" -lt 10 ] && fair=10
  echo "fuzz/run-ci.sh: ${#targets[@]} targets in a ${budget}s budget (build took ${elapsed}s): ${fair}s each"
  seconds=$fair
fi

work=$(mktemp -d)
trap 'rm -rf "$probe" "$work"' EXIT

# run_one TARGET: fuzz one target; writes $work/TARGET.summary and .rc
run_one() {
  local t=$1 name=${1#fuzz_}
  local dir=$work/$t
  mkdir -p "$dir/corpus" "$artifacts/$t"
  local max_len=4096
  if [ -f "fuzz/$t.options" ]; then
    max_len=$(sed -n 's/^max_len *= *\([0-9]*\).*/\1/p' "fuzz/$t.options")
  fi
  local seeds=()
  for s in "fuzz/corpus/$name" "fuzz/regressions/$name"; do
    [ -d "$s" ] && seeds+=("$s")
  done
  local rc=0
  "$build/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$max_len" -dict="$dict" -print_final_stats=1 \
    -artifact_prefix="$artifacts/$t/" "$dir/corpus" "${seeds[@]}" \
    >"$dir/log" 2>&1 || rc=$?
  local last stats runs eps
  last=$(grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE|INITED)' "$dir/log" | tail -n 1 || true)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log")
  eps=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log")
  stats=$(echo "$last" | grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+' || true)
  if [ $rc -eq 0 ]; then
    echo "$t: ok, ${runs:-?} runs, ${eps:-?} exec/s, ${stats:-no stats}, ${seconds}s" >"$dir.summary"
  else
    local why
    why=$(grep -oE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer): [a-zA-Z-]+' "$dir/log" | head -n 1 || true)
    [ -z "$why" ] && why=$(grep -m1 -E 'fuzz check failed|runtime error' "$dir/log" || true)
    echo "$t: FAILED (exit $rc): ${why:-see log}; input kept in $artifacts/$t/" >"$dir.summary"
    {
      echo "---- $t log (last 40 lines) ----"
      tail -n 40 "$dir/log"
    } >"$dir.failure"
  fi
  echo $rc >"$dir.rc"
}

running=0
for t in "${targets[@]}"; do
  if [ ! -x "$build/$t" ]; then
    echo "fuzz/run-ci.sh: no target $t in $build" >&2
    exit 1
  fi
  run_one "$t" &
  running=$((running + 1))
  if [ $running -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
done
wait || true

failed=0
echo "fuzz/run-ci.sh: ${#targets[@]} target(s), ${seconds}s each, $jobs at a time"
for t in "${targets[@]}"; do
  cat "$work/$t.summary"
  if [ "$(cat "$work/$t.rc")" != 0 ]; then
    failed=1
    cat "$work/$t.failure"
  fi
done
echo "fuzz/run-ci.sh: done in $(( $(date +%s) - started ))s"
exit $failed
