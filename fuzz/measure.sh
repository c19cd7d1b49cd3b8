#!/usr/bin/env bash
# Measures fuzz targets for the README tables: exec/s (libFuzzer's
# average_exec_per_sec) and coverage (cov/ft/corpus of the final DONE line)
# after a fixed time, starting from the checked-in corpus, -seed=1. Targets
# with the custom mutator run twice, with it and without it
# (TOPKIT_FUZZ_NO_MUTATOR=1, same binary), unless TOPKIT_MEASURE_PLAIN=0.
# Needs the `fuzz` preset built.
#
#   fuzz/measure.sh [SECONDS] [TARGET...]      # default 300 s, all targets
#
# Environment:
#   TOPKIT_MEASURE_BIN=DIR   binaries (and, if there, <target>.options and
#                            top.dict) from DIR instead of build/fuzz/fuzz:
#                            keep a copy of an old build to compare with
#   TOPKIT_MEASURE_CPUS=1    pin runs with taskset, one run per listed CPU at
#                            a time (e.g. "1", or "0 1"); default: two runs
#                            at a time, unpinned
#   TOPKIT_MEASURE_PLAIN=0   skip the TOPKIT_FUZZ_NO_MUTATOR runs
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
build=${TOPKIT_MEASURE_BIN:-build/fuzz/fuzz}
read -r -a cpus <<<"${TOPKIT_MEASURE_CPUS:-}"
plain=${TOPKIT_MEASURE_PLAIN:-1}
if [ $# -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(find "$build" -maxdepth 1 -type f -name 'fuzz_*' -perm -u+x -printf '%f\n' | sort)
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
dict=$build/top.dict
[ -f "$dict" ] || dict=build/fuzz/fuzz/top.dict

# uses_mutator TARGET: true when the target defines LLVMFuzzerCustomMutator.
uses_mutator() { [[ $(nm -C "$build/$1" 2>/dev/null) == *' T LLVMFuzzerCustomMutator'* ]]; }

run() {  # run SLOT TARGET VARIANT
  local slot=$1 t=$2 v=$3 name=${2#fuzz_} max_len=4096 opts=fuzz/$2.options
  [ -f "$build/$t.options" ] && opts=$build/$t.options
  [ -f "$opts" ] && max_len=$(sed -n 's/^max_len *= *\([0-9]*\).*/\1/p' "$opts")
  local dir=$work/$t.$v
  mkdir -p "$dir/corpus"
  local pre=()
  [ "$v" = plain ] && pre=(env TOPKIT_FUZZ_NO_MUTATOR=1)
  [ ${#cpus[@]} -gt 0 ] && pre+=(taskset -c "${cpus[$slot]}")
  "${pre[@]}" "$build/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$max_len" -dict="$dict" -print_final_stats=1 -seed=1 \
    "$dir/corpus" "fuzz/corpus/$name" >"$dir/log" 2>&1 || echo "$t $v: exit $?" >&2
  local last eps
  last=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$dir/log" | tail -n 1)
  eps=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log")
  echo "$t|$v|$eps|$(echo "$last" | grep -oE 'cov: [0-9]+' | cut -d' ' -f2)|$(echo "$last" | grep -oE 'ft: [0-9]+' | cut -d' ' -f2)|$(echo "$last" | grep -oE 'corp: [0-9]+' | cut -d' ' -f2)" >"$dir.row"
}

jobs=()
for t in "${targets[@]}"; do
  if [ "$plain" != 0 ] && uses_mutator "$t"; then
    jobs+=("$t custom" "$t plain")
  elif uses_mutator "$t"; then
    jobs+=("$t custom")
  else
    jobs+=("$t none")
  fi
done
slots=2
[ ${#cpus[@]} -gt 0 ] && slots=${#cpus[@]}
# One background loop per slot, each taking every slots-th job in turn, so a
# pinned CPU never runs two of ours at once.
for ((s = 0; s < slots; s++)); do
  (
    for ((i = s; i < ${#jobs[@]}; i += slots)); do
      # shellcheck disable=SC2086
      run "$s" ${jobs[$i]}
    done
  ) &
done
wait
echo "| target | mutator | exec/s | cov | ft | corpus |"
echo "|---|---|---:|---:|---:|---:|"
for t in "${targets[@]}"; do
  for v in custom plain none; do
    [ -f "$work/$t.$v.row" ] || continue
    IFS='|' read -r a b c d e f <"$work/$t.$v.row"
    echo "| $a | $b | $c | $d | $e | $f |"
  done
done
