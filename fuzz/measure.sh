#!/usr/bin/env bash
# Measures fuzz targets for the README tables: exec/s (libFuzzer's
# average_exec_per_sec, wall clock), runs per CPU second (runs / (user +
# sys) of the process: what the target costs, whatever else the machine
# runs) and coverage (cov/ft/corpus of the final DONE line) after a fixed
# time, starting from the checked-in corpus, -seed=1, with the flags of the
# target's .options ([libfuzzer] section, dictionary from the build).
# Needs the `fuzz` preset built.
#
#   fuzz/measure.sh [SECONDS] [TARGET...]      # default 300 s, all targets
#
# Two runs at a time, pinned to CPUs 0 and 1 (taskset), one target at a
# time. Targets with the custom mutator run with it and without it
# (TOPKIT_FUZZ_NO_MUTATOR=1, same binary) side by side.
#
# Before/after: TOPKIT_MEASURE_BIN="OLD NEW" (two directories, each with the
# fuzz_* binaries, their .options and top.dict, e.g. a copy of
# build/fuzz/fuzz plus fuzz/*.options from before a change) runs each
# target from both side by side instead (the mutator as built), OLD on CPU 0
# and NEW on CPU 1 for even-numbered targets and the other way round for
# odd ones, so both share whatever load the machine has.
#
# Coverage measured by one binary: builds that instrument different code
# (fuzz/coverage-ignorelist.txt leaves the standard library's and other
# header-only libraries' functions out) count cov/ft differently, so
# TOPKIT_MEASURE_RECOV=DIR replays each run's final corpus (its new inputs
# and the seeds) through DIR's build of the target (-runs=0) and adds the
# cov/ft that build counts on it: the same yardstick for both runs.
#
# The host: this VM's two CPUs are not steady. The same binary, alone,
# -seed=1, runs fuzz_frame at 115k exec/s and a minute later, on either
# CPU, at 71k (docs/perf/fuzz-speed.md, "Speed, eighth pass"). So each run is timed
# with a probe before and after: a fixed awk loop on the same CPU, its
# user seconds in the `probe` column (0.24-0.31 s on a CPU in its usual
# state, 0.32-0.45 s when the host slows it). TOPKIT_MEASURE_REPEAT=N runs
# every target N times, changing CPU each time, and prints each run on its own
# line with its probe, then the best and the median of the N: a run
# slowed by the host shows in its probe, not only in its exec/s.
#
# Environment:
#   TOPKIT_MEASURE_BIN=DIR...  binaries (default build/fuzz/fuzz, options
#                              then from fuzz/)
#   TOPKIT_MEASURE_REPEAT=N    runs per target and variant (default 1)
#   TOPKIT_MEASURE_RECOV=DIR   also count each final corpus's coverage with
#                              DIR's binaries
#   TOPKIT_MEASURE_CPUS="0 1"  the two CPUs to pin to
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-300}
shift || true
read -r -a bins <<<"${TOPKIT_MEASURE_BIN:-build/fuzz/fuzz}"
read -r -a cpus <<<"${TOPKIT_MEASURE_CPUS:-0 1}"
repeat=${TOPKIT_MEASURE_REPEAT:-1}
if ! [[ $repeat =~ ^[1-9][0-9]*$ ]]; then
  echo "fuzz/measure.sh: TOPKIT_MEASURE_REPEAT must be a whole number of runs, 1 or more (got \"$repeat\")" >&2
  exit 2
fi
if [ $# -gt 0 ]; then
  targets=("$@")
else
  mapfile -t targets < <(find "${bins[0]}" -maxdepth 1 -type f -name 'fuzz_*' -perm -u+x -printf '%f\n' | sort)
fi
# On tmpfs when there is one, as fuzz/run-ci.sh: creating a file for each
# new input on the VM's ext4 /tmp is a measurable part of a run.
work=$(mktemp -d -p /dev/shm topkit-measure.XXXXXX 2>/dev/null || mktemp -d)
trap 'rm -rf "$work"' EXIT

# uses_mutator BIN TARGET: true when the target defines LLVMFuzzerCustomMutator.
uses_mutator() { [[ $(nm -C "$1/$2" 2>/dev/null) == *' T LLVMFuzzerCustomMutator'* ]]; }

# flags BIN TARGET: the [libfuzzer] section of the target's options as flags.
flags() {
  local opts=$1/$2.options dict=$1/top.dict
  [ -f "$opts" ] || opts=fuzz/$2.options
  [ -f "$dict" ] || dict=build/fuzz/fuzz/top.dict
  awk -v dict="$dict" '
    /^\[/ { section = $0; next }
    section == "[libfuzzer]" && /=/ {
      key = $0; sub(/[ \t]*=.*/, "", key); gsub(/^[ \t]+/, "", key)
      val = $0; sub(/^[^=]*=[ \t]*/, "", val); sub(/[ \t]+$/, "", val)
      if (key == "dict") val = dict
      printf "-%s=%s\n", key, val
    }' "$opts"
}

# probe CPU: user seconds of a fixed loop on CPU (the host's state now).
probe() {
  local TIMEFORMAT=%3U
  { time taskset -c "$1" awk 'BEGIN { for (i = 0; i < 6000000; i++) s += i % 7 }'; } 2>&1
}

run() {  # run CPU BIN TARGET VARIANT LABEL REP
  local cpu=$1 bin=$2 t=$3 v=$4 label=$5 rep=${6:-0} name=${3#fuzz_}
  local dir=$work/$t.$label.$v.r$rep
  mkdir -p "$dir/corpus"
  local speed after
  speed=$(probe "$cpu")
  local pre=(taskset -c "$cpu")
  [ "$v" = plain ] && pre=(env TOPKIT_FUZZ_NO_MUTATOR=1 "${pre[@]}")
  local f=()
  mapfile -t f < <(flags "$bin" "$t")
  /usr/bin/time -f '%U %S' -o "$dir/time" "${pre[@]}" "$bin/$t" "${f[@]}" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -seed=1 \
    "$dir/corpus" "fuzz/corpus/$name" >"$dir/log" 2>&1 || echo "$t $label $v: exit $?" >&2
  after=$(probe "$cpu")
  local last eps runs cpu_s
  last=$(grep -E '^#[0-9]+[[:space:]]+DONE' "$dir/log" | tail -n 1)
  eps=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log")
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log")
  cpu_s=$(awk '{print $1 + $2}' "$dir/time")
  local recov=""
  if [ -n "${TOPKIT_MEASURE_RECOV:-}" ]; then
    taskset -c "$cpu" "$TOPKIT_MEASURE_RECOV/$t" "${f[@]}" -runs=0 -timeout=10 -rss_limit_mb=2048 \
      "$dir/corpus" "fuzz/corpus/$name" >"$dir/recov" 2>&1 || true
    recov=$(grep -E '^#[0-9]+[[:space:]]+INITED' "$dir/recov" | tail -n 1 | grep -oE 'cov: [0-9]+ ft: [0-9]+' |
      sed 's/cov: //; s/ ft: / \/ /')
  fi
  echo "$t|$label|$v|$eps|$(awk -v r="$runs" -v c="$cpu_s" 'BEGIN { printf "%d", (c > 0 ? r / c : 0) }')|$(echo "$last" | grep -oE 'cov: [0-9]+' | cut -d' ' -f2)|$(echo "$last" | grep -oE 'ft: [0-9]+' | cut -d' ' -f2)|$(echo "$last" | grep -oE 'corp: [0-9]+' | cut -d' ' -f2)|$recov|$cpu|$speed / $after" >"$dir.row"
}

# Repetition r of a target puts each of its runs on the other CPU from
# repetition r - 1.
for ((r = 0; r < repeat; r++)); do
  i=0
  single=0  # targets without a mutator run two at a time
  for t in "${targets[@]}"; do
    x=$(((i + r) % 2))
    if [ ${#bins[@]} -ge 2 ]; then
      run "${cpus[0]}" "${bins[$x]}" "$t" built "b$x" "$r" &
      run "${cpus[1]}" "${bins[$((1 - x))]}" "$t" built "b$((1 - x))" "$r" &
      wait
    elif uses_mutator "${bins[0]}" "$t"; then
      wait
      single=0
      run "${cpus[$x]}" "${bins[0]}" "$t" custom b0 "$r" &
      run "${cpus[$((1 - x))]}" "${bins[0]}" "$t" plain b0 "$r" &
      wait
    else
      run "${cpus[$(((single + r) % 2))]}" "${bins[0]}" "$t" none b0 "$r" &
      single=$((1 - single))
      [ $single = 0 ] && wait
    fi
    i=$((i + 1))
  done
  wait
done
wait
echo "| target | build | mutator | exec/s | runs/CPU-s | cov | ft | corpus | cov / ft by ${TOPKIT_MEASURE_RECOV:-(none)} | CPU | probe s |"
echo "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for t in "${targets[@]}"; do
  for b in "${!bins[@]}"; do
    for v in built custom plain none; do
      [ -f "$work/$t.b$b.$v.r0.row" ] || continue
      all=()
      for ((r = 0; r < repeat; r++)); do
        IFS='|' read -r c1 c2 c3 c4 c5 c6 c7 c8 c9 c10 c11 <"$work/$t.b$b.$v.r$r.row"
        echo "| $c1 | ${bins[$b]} | $c3 | $c4 | $c5 | $c6 | $c7 | $c8 | ${c9:--} | $c10 | $c11 |"
        all+=("$c4")
      done
      if [ "$repeat" -gt 1 ]; then
        printf '%s\n' "${all[@]}" | sort -n | awk -v t="$t" -v b="${bins[$b]}" -v v="$v" '
          { x[NR] = $1 }
          END { m = (NR % 2) ? x[(NR + 1) / 2] : int((x[NR / 2] + x[NR / 2 + 1]) / 2)
                printf "| %s | %s | %s | best %d, median %d of %d | | | | | | | |\n", t, b, v, x[NR], m, NR }'
      fi
    done
  done
done
