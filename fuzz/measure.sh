#!/usr/bin/env bash
# Measures every protocol target for the README table: exec/s and coverage
# (cov/ft/corpus from libFuzzer's final stats) after a fixed time, with the
# custom mutator and without it (TOPKIT_FUZZ_NO_MUTATOR=1, same binary).
# Two runs at a time; the two variants of a target run side by side, so they
# share whatever load the machine has. Needs the `fuzz` preset built.
#
#   fuzz/measure.sh [SECONDS] [TARGET...]      # default 300 s, all targets
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
build=build/fuzz/fuzz
if [ $# -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(find "$build" -maxdepth 1 -type f -name 'fuzz_*' -perm -u+x -printf '%f\n' | sort)
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# uses_mutator TARGET: true when the target defines LLVMFuzzerCustomMutator.
uses_mutator() { [[ $(nm -C "$build/$1" 2>/dev/null) == *' T LLVMFuzzerCustomMutator'* ]]; }

run() {  # run TARGET VARIANT
  local t=$1 v=$2 name=${1#fuzz_} max_len=4096
  [ -f "fuzz/$t.options" ] && max_len=$(sed -n 's/^max_len *= *\([0-9]*\).*/\1/p' "fuzz/$t.options")
  local dir=$work/$t.$v
  mkdir -p "$dir/corpus"
  local env=()
  [ "$v" = plain ] && env=(env TOPKIT_FUZZ_NO_MUTATOR=1)
  "${env[@]}" "$build/$t" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
    -max_len="$max_len" -dict="$build/top.dict" -print_final_stats=1 -seed=1 \
    "$dir/corpus" "fuzz/corpus/$name" >"$dir/log" 2>&1 || echo "$t $v: exit $?" >&2
  local last eps
  last=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$dir/log" | tail -n 1)
  eps=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log")
  echo "$t|$v|$eps|$(echo "$last" | grep -oE 'cov: [0-9]+' | cut -d' ' -f2)|$(echo "$last" | grep -oE 'ft: [0-9]+' | cut -d' ' -f2)|$(echo "$last" | grep -oE 'corp: [0-9]+' | cut -d' ' -f2)" >"$dir.row"
}

jobs=()
for t in "${targets[@]}"; do
  if uses_mutator "$t"; then
    jobs+=("$t custom" "$t plain")
  else
    jobs+=("$t none")
  fi
done
running=0
for j in "${jobs[@]}"; do
  run $j &
  running=$((running + 1))
  if [ $running -ge 2 ]; then
    wait -n || true
    running=$((running - 1))
  fi
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
