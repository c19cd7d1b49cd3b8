#!/usr/bin/env bash
# CI fuzzing, the way ClusterFuzzLite builds and runs the targets: runs
# .clusterfuzzlite/build.sh in an OSS-Fuzz-like environment (CC/CXX clang,
# the address sanitizer's CFLAGS/CXXFLAGS with -fsanitize=fuzzer-no-link,
# LIB_FUZZING_ENGINE=-fsanitize=fuzzer, SRC and OUT temporary), checks that
# OUT holds every target with its .options, dictionary and seed corpus zip,
# then runs each binary from OUT for a few seconds on its unzipped seed
# corpus with the flags its .options gives (the dictionary taken from OUT),
# two at a time. New inputs go to a temporary directory. Fails on a build.sh
# failure, a missing file in OUT, an object instrumented otherwise than
# fuzz/CMakeLists.txt asks (the output room without compare tracing, the
# capture readers with it), or any crash, leak, timeout (-timeout=10)
# or out-of-memory (-rss_limit_mb=2560, ClusterFuzzLite's). Prints one line
# per target. Skips, with a message, when clang++ or libFuzzer is missing.
#
#   fuzz/run-ci.sh                   # every target, 5 s each
#   TOPKIT_FUZZ_SECONDS=60 TOPKIT_FUZZ_JOBS=1 fuzz/run-ci.sh fuzz_frame
#
# The build goes to build/oss (build.sh's directory, kept between runs, so a
# second run only rebuilds what changed). Crash inputs are kept under
# build/oss/artifacts/<target>/ (turn each into a named regression under
# fuzz/regressions/<target>/, see README.md).
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd -P)

seconds=${TOPKIT_FUZZ_SECONDS:-5}
jobs=${TOPKIT_FUZZ_JOBS:-2}

if ! command -v clang++ >/dev/null 2>&1; then
  echo "fuzz/run-ci.sh: SKIPPED: clang++ not found (install clang and libclang-rt-14-dev to fuzz)"
  exit 0
fi
tmp=$(mktemp -d)
# The fuzzers' working corpora (every new input is a file created, and in a
# 5 s run most of the time is early discovery): on tmpfs when there is one.
# On an ext4 /tmp creating a file costs kernel time the targets feel
# (docs/perf/decisions.md, "Working corpora on tmpfs").
rundirs=$(mktemp -d -p /dev/shm topkit-fuzz.XXXXXX 2>/dev/null || mktemp -d)
trap 'rm -rf "$tmp" "$rundirs"' EXIT
printf 'extern "C" int LLVMFuzzerTestOneInput(const unsigned char*, unsigned long) { return 0; }\n' \
  >"$tmp/probe.cpp"
if ! clang++ -fsanitize=fuzzer "$tmp/probe.cpp" -o "$tmp/probe" >/dev/null 2>&1; then
  echo "fuzz/run-ci.sh: SKIPPED: clang++ cannot link -fsanitize=fuzzer (libFuzzer runtime missing: libclang-rt-14-dev)"
  exit 0
fi
if ! command -v zip >/dev/null 2>&1; then
  echo "fuzz/run-ci.sh: zip is needed (build.sh zips the seed corpora; scripts/install-deps.sh installs it)" >&2
  exit 1
fi

started=$(date +%s)
# OSS-Fuzz's environment for an address-sanitizer libFuzzer build
# (infra/base-images/base-builder: SANITIZER_FLAGS_address, COVERAGE_FLAGS).
mkdir -p "$tmp/src" "$tmp/out" "$tmp/work"
# A build directory configured from another source path cannot be reused.
if [ -f build/oss/CMakeCache.txt ] &&
  ! grep -qx "CMAKE_HOME_DIRECTORY:INTERNAL=$root" build/oss/CMakeCache.txt; then
  rm -rf build/oss
fi
ln -s "$root" "$tmp/src/topkit"
sanitizer_flags="-fsanitize=address -fsanitize-address-use-after-scope -fsanitize=fuzzer-no-link"
flags="-O1 -fno-omit-frame-pointer -gline-tables-only $sanitizer_flags"
echo "fuzz/run-ci.sh: .clusterfuzzlite/build.sh (SANITIZER=address, OUT=$tmp/out)"
env SRC="$tmp/src" OUT="$tmp/out" WORK="$tmp/work" \
  CC=clang CXX=clang++ CFLAGS="$flags" CXXFLAGS="$flags" \
  LIB_FUZZING_ENGINE=-fsanitize=fuzzer SANITIZER=address FUZZING_ENGINE=libfuzzer \
  ARCHITECTURE=x86_64 \
  bash -eu "$root/.clusterfuzzlite/build.sh"
out=$tmp/out
artifacts=build/oss/artifacts
rm -rf "$artifacts"
built=$(($(date +%s) - started))

# Every target (one fuzz/fuzz_<target>.options each) must be in OUT with
# what ClusterFuzzLite reads next to it.
missing=0
all=()
for o in fuzz/fuzz_*.options; do
  t=$(basename "$o" .options)
  all+=("$t")
  name=${t#fuzz_}
  need=("$t" "$t.options" "$t.dict")
  [ -d "fuzz/corpus/$name" ] || [ -d "fuzz/regressions/$name" ] && need+=("${t}_seed_corpus.zip")
  for f in "${need[@]}"; do
    if [ ! -s "$out/$f" ]; then
      echo "fuzz/run-ci.sh: build.sh left no $f in OUT" >&2
      missing=1
    fi
  done
done
[ -s "$out/top.dict" ] || { echo "fuzz/run-ci.sh: build.sh left no top.dict in OUT" >&2; missing=1; }
[ $missing = 0 ] || exit 1

# The instrumentation fuzz/CMakeLists.txt chooses: the output room's
# objects keep their edge counters without compare tracing; the capture
# readers (parsers) keep both.
instrumented() {  # instrumented ROOM_DIR WANT_CMP: every object of the room as asked
  local bad=0 o syms
  for o in build/oss/analyzer/CMakeFiles/$1.dir/*/src/*.o; do
    [ -f "$o" ] || { echo "fuzz/run-ci.sh: no objects of $1 in build/oss" >&2; return 1; }
    syms=$(nm "$o")
    if ! grep -q __sanitizer_cov_8bit_counters_init <<<"$syms"; then
      echo "fuzz/run-ci.sh: $o has no edge counters" >&2
      bad=1
    fi
    if grep -qE '__sanitizer_cov_trace_(const_)?cmp' <<<"$syms"; then
      [ "$2" = yes ] || { echo "fuzz/run-ci.sh: $o traces compares (fuzz/CMakeLists.txt turns that off for $1)" >&2; bad=1; }
    else
      [ "$2" = no ] || { echo "fuzz/run-ci.sh: $o traces no compares" >&2; bad=1; }
    fi
  done
  return $bad
}
instrumented topdump_output no && instrumented topdump_capture yes || exit 1

if [ $# -gt 0 ]; then
  targets=("$@")
else
  targets=("${all[@]}")
fi

# libfuzzer_flags TARGET: the [libfuzzer] section of OUT/TARGET.options as
# flags, a dictionary named there taken from OUT (as ClusterFuzzLite does).
libfuzzer_flags() {
  awk -v out="$out" '
    /^\[/ { section = $0; next }
    section == "[libfuzzer]" && /=/ {
      key = $0; sub(/[ \t]*=.*/, "", key); gsub(/^[ \t]+/, "", key)
      val = $0; sub(/^[^=]*=[ \t]*/, "", val); sub(/[ \t]+$/, "", val)
      if (key == "dict") val = out "/" val
      printf "-%s=%s\n", key, val
    }' "$out/$1.options"
}

# run_one TARGET: fuzz one target; writes $tmp/TARGET.summary and .rc
run_one() {
  local t=$1
  local dir=$rundirs/$t
  mkdir -p "$dir/corpus" "$dir/seeds" "$artifacts/$t"
  # python3's zipfile: unzip is not among scripts/install-deps.sh's packages.
  [ -f "$out/${t}_seed_corpus.zip" ] && python3 -m zipfile -e "$out/${t}_seed_corpus.zip" "$dir/seeds"
  local flags=()
  mapfile -t flags < <(libfuzzer_flags "$t")
  local rc=0
  (cd "$dir" && "$out/$t" "${flags[@]}" -max_total_time="$seconds" -timeout=10 \
    -rss_limit_mb=2560 -print_final_stats=1 -artifact_prefix="$root/$artifacts/$t/" \
    corpus seeds >log 2>&1) || rc=$?
  local last stats runs eps
  last=$(grep -E '^#[0-9]+[[:space:]]+(DONE|pulse|NEW|REDUCE|INITED)' "$dir/log" | tail -n 1 || true)
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$dir/log")
  eps=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$dir/log")
  stats=$(echo "$last" | grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+' || true)
  if [ $rc -eq 0 ]; then
    echo "$t: ok, ${runs:-?} runs, ${eps:-?} exec/s, ${stats:-no stats}, ${seconds}s" >"$tmp/$t.summary"
  else
    local why
    why=$(grep -oE 'ERROR: (libFuzzer|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer): [a-zA-Z-]+' "$dir/log" | head -n 1 || true)
    [ -z "$why" ] && why=$(grep -m1 -E 'fuzz check failed|runtime error' "$dir/log" || true)
    echo "$t: FAILED (exit $rc): ${why:-see log}; input kept in $artifacts/$t/" >"$tmp/$t.summary"
    {
      echo "---- $t log (last 40 lines) ----"
      tail -n 40 "$dir/log"
    } >"$tmp/$t.failure"
  fi
  echo $rc >"$tmp/$t.rc"
}

running=0
for t in "${targets[@]}"; do
  if [ ! -x "$out/$t" ]; then
    echo "fuzz/run-ci.sh: no target $t in OUT" >&2
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
echo "fuzz/run-ci.sh: ${#targets[@]} target(s) from build.sh's OUT, ${seconds}s each, $jobs at a time"
for t in "${targets[@]}"; do
  cat "$tmp/$t.summary"
  if [ "$(cat "$tmp/$t.rc")" != 0 ]; then
    failed=1
    cat "$tmp/$t.failure"
  fi
done
echo "fuzz/run-ci.sh: done in $(($(date +%s) - started))s (build.sh ${built}s)"
exit $failed
