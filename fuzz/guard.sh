#!/usr/bin/env bash
# The capture targets' throughput guard (issue 48): the instructions each
# costs per input on fixed inputs, counted by callgrind, against the budget
# recorded in fuzz/guard/budget.txt. Exits 1 when a target is over it.
# Counted, not timed: exec/s on this VM moves threefold with the other jobs
# (docs/perf/fuzz-speed.md), an instruction count does not move at all.
# Run by hand (a few minutes; not in CI's time limit):
#
#   fuzz/guard.sh [TARGET...]            # default: the five capture targets
#   fuzz/guard.sh --record [TARGET...]   # write the counts as the new budget
#
# Inputs: fuzz/guard/<name>/, inputs recorded from a fuzzing run and kept
# fixed (libFuzzer's own loop is not: -seed=1 -runs=3000 reached cov
# 3,291-3,406 in three runs of one binary, so its inputs and their cost
# differ run to run). Each target runs them once as libFuzzer runs a
# corpus (-runs=0, its .options flags), under callgrind. Two figures per
# input, each with its tolerance in the budget:
#   target  LLVMFuzzerTestOneInput with everything under it: the analyzer,
#           the readers and the harness's JSON check;
#   loop    the whole process: the target and libFuzzer's feature work on
#           what it covered (which grows with the edges the target reaches:
#           docs/perf/fuzz-speed.md, "Issue 48"), startup included.
# The counts belong to a toolchain (clang, libstdc++, valgrind): the budget
# names the one it was recorded with, and the guard says when it differs.
#
# The build: build/fuzz-count, the `fuzz` preset's flags without the
# address sanitizer (valgrind cannot run ASan binaries) and with DWARF 4
# (valgrind 3.19 cannot read clang 14's DWARF 5); TOPKIT_GUARD_BUILD=DIR
# uses another build with those flags. TOPKIT_GUARD_JOBS (default 2)
# targets run at a time; TOPKIT_GUARD_BUDGET=FILE reads (or records)
# another budget.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd -P)
record=0
if [ "${1:-}" = --record ]; then
  record=1
  shift
fi
budget=${TOPKIT_GUARD_BUDGET:-fuzz/guard/budget.txt}
if [ $# -gt 0 ]; then
  targets=("$@")
else
  targets=(fuzz_capture_lines fuzz_capture_pcap fuzz_capture_raw fuzz_capture_saleae fuzz_capture_socat)
fi
jobs=${TOPKIT_GUARD_JOBS:-2}
for tool in valgrind clang++ python3; do
  command -v "$tool" >/dev/null || { echo "fuzz/guard.sh: $tool is needed" >&2; exit 2; }
done
for t in "${targets[@]}"; do
  [ -d "fuzz/guard/${t#fuzz_}" ] || { echo "fuzz/guard.sh: no inputs fuzz/guard/${t#fuzz_}/ for $t" >&2; exit 2; }
done

build=${TOPKIT_GUARD_BUILD:-build/fuzz-count}
if [ -z "${TOPKIT_GUARD_BUILD:-}" ]; then
  launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
    -DTOPKIT_FUZZ=ON -DTOPKIT_TESTS=OFF -DTOPKIT_TOOLS=ON -DTOPKIT_BENCH=OFF "${launcher[@]}" \
    "-DCMAKE_CXX_FLAGS=-fsanitize=fuzzer-no-link,undefined -fno-omit-frame-pointer -gdwarf-4 -fsanitize-coverage-ignorelist=$root/fuzz/coverage-ignorelist.txt" \
    >/dev/null
  echo "fuzz/guard.sh: building ${targets[*]} in $build"
  cmake --build "$build" -j "$jobs" --target "${targets[@]}" >/dev/null
fi
toolchain="$(clang++ --version | head -n 1); $(valgrind --version)"

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# flags TARGET: the [libfuzzer] section of the target's .options as flags,
# as fuzz/measure.sh reads them, but the dictionary: -runs=0 mutates
# nothing.
flags() {
  awk '
    /^\[/ { section = $0; next }
    section == "[libfuzzer]" && /=/ {
      key = $0; sub(/[ \t]*=.*/, "", key); gsub(/^[ \t]+/, "", key)
      val = $0; sub(/^[^=]*=[ \t]*/, "", val); sub(/[ \t]+$/, "", val)
      if (key != "dict") printf "-%s=%s\n", key, val
    }' "fuzz/$1.options"
}

# count TARGET: "<inputs> <loop per input> <target per input>" into $work/TARGET.
count() {
  local t=$1 f=()
  mapfile -t f < <(flags "$t")
  mkdir -p "$work/$t.out"
  valgrind --tool=callgrind --callgrind-out-file="$work/$t.cg" "$build/fuzz/$t" "${f[@]}" \
    -runs=0 -seed=1 -timeout=600 -rss_limit_mb=4096 "$work/$t.out" "fuzz/guard/${t#fuzz_}" \
    >"$work/$t.log" 2>&1 || { echo "fuzz/guard.sh: $t failed:" >&2; tail -n 20 "$work/$t.log" >&2; return 1; }
  # Total instructions, and the calls of LLVMFuzzerTestOneInput with the
  # instructions under them (callgrind's calls= lines, names compressed).
  python3 - "$work/$t.cg" >"$work/$t" <<'EOF'
import re, sys
names, fn, callee, after_calls = {}, None, None, False
total = calls = inside = 0
for line in open(sys.argv[1]):
    if after_calls:
        if callee == "LLVMFuzzerTestOneInput" and fn != callee:
            inside += int(line.split()[1])
        after_calls = False
        continue
    m = re.match(r"(c?fn)=\((\d+)\)(?: (.*))?", line)
    if m:
        if m.group(3):
            names[m.group(2)] = m.group(3).strip()
        name = names.get(m.group(2), "")
        if m.group(1) == "fn":
            fn = name
        else:
            callee = name
        continue
    if line.startswith("calls="):
        after_calls = True
        if callee == "LLVMFuzzerTestOneInput" and fn != callee:
            calls += int(line[6:].split()[0])
    elif line.startswith(("summary:", "totals:")):
        total = int(line.split()[1])
if not calls:
    sys.exit("no call of LLVMFuzzerTestOneInput counted")
print(calls, round(total / calls), round(inside / calls))
EOF
}

failed=0
running=0
for t in "${targets[@]}"; do
  count "$t" &
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then
    wait -n || failed=1
    running=$((running - 1))
  fi
done
while [ "$running" -gt 0 ]; do
  wait -n || failed=1
  running=$((running - 1))
done
[ "$failed" = 0 ] || exit 2

if [ "$record" = 1 ]; then
  {
    echo "# fuzz/guard.sh's budget: instructions per input on fuzz/guard/<name>/ (-runs=0),"
    echo "# callgrind; recorded by fuzz/guard.sh --record on $(git rev-parse --short HEAD 2>/dev/null || echo '?'), $(date -u +%Y-%m-%d)."
    echo "# A target fails when a figure is over its recorded value by more than the tolerance."
    echo "toolchain $toolchain"
    echo "tolerance target 5"
    echo "tolerance loop 10"
    echo "# target inputs loop target"
    for t in "${targets[@]}"; do echo "$t $(cat "$work/$t")"; done
  } >"$budget.new"
  # keep the rows of targets not measured now
  if [ -f "$budget" ]; then
    awk 'NR == FNR { if ($1 ~ /^fuzz_/) seen[$1] = 1; next } $1 ~ /^fuzz_/ && !($1 in seen)' \
      "$budget.new" "$budget" >>"$budget.new"
  fi
  mv "$budget.new" "$budget"
  echo "fuzz/guard.sh: recorded $budget"
  cat "$budget"
  exit 0
fi

[ -f "$budget" ] || { echo "fuzz/guard.sh: no $budget (fuzz/guard.sh --record)" >&2; exit 2; }
recorded_toolchain=$(sed -n 's/^toolchain //p' "$budget")
if [ "$recorded_toolchain" != "$toolchain" ]; then
  echo "fuzz/guard.sh: NOTE: the budget was recorded with \"$recorded_toolchain\"," \
    "this is \"$toolchain\": counts differ between toolchains"
fi
tol_target=$(awk '$1 == "tolerance" && $2 == "target" { print $3 }' "$budget")
tol_loop=$(awk '$1 == "tolerance" && $2 == "loop" { print $3 }' "$budget")
echo "| target | inputs | loop / input | budget | change | target / input | budget | change | |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|---|"
status=0
for t in "${targets[@]}"; do
  read -r n loop inside <"$work/$t"
  row=$(awk -v t="$t" '$1 == t' "$budget")
  if [ -z "$row" ]; then
    echo "| $t | $n | $loop | - | | $inside | - | | no budget |"
    status=1
    continue
  fi
  read -r _ bn bloop binside <<<"$row"
  verdict=$(awk -v l="$loop" -v bl="$bloop" -v i="$inside" -v bi="$binside" -v tl="$tol_loop" \
    -v ti="$tol_target" -v n="$n" -v bn="$bn" 'BEGIN {
      cl = 100 * (l / bl - 1); ci = 100 * (i / bi - 1); v = "ok"
      if (n != bn) v = "inputs changed (" bn " recorded)"
      else if (ci > ti || cl > tl) v = "OVER BUDGET"
      else if (ci < -ti || cl < -tl) v = "under: record a new budget (fuzz/guard.sh --record)"
      printf "%+.1f%%|%+.1f%%|%s", cl, ci, v }')
  IFS='|' read -r cl ci v <<<"$verdict"
  echo "| $t | $n | $loop | $bloop | $cl | $inside | $binside | $ci | $v |"
  case $v in ok | under*) ;; *) status=1 ;; esac
done
echo "(tolerance: target +$tol_target%, loop +$tol_loop%; $budget)"
exit $status
