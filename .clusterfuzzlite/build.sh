#!/bin/bash -eu
# ClusterFuzzLite / OSS-Fuzz build script. Follows the OSS-Fuzz conventions:
# compilers and flags from $CC $CXX $CFLAGS $CXXFLAGS (sanitizer and coverage
# flags included), the engine from $LIB_FUZZING_ENGINE, everything into $OUT:
# the fuzz_* binaries, <target>_seed_corpus.zip, <target>.options and the
# dictionary generated from the catalog (top.dict, also as <target>.dict).
cd "$SRC/topkit"
# The physical path: fuzz/run-ci.sh links a temporary $SRC/topkit to the
# checkout, and the build directory's cache must name the same source each run.
cd "$(pwd -P)"

# Coverage instrumentation only for our code, not the standard library's
# or the header-only libraries' templates (fuzz/coverage-ignorelist.txt;
# docs/perf/fuzz-speed.md, "Speed, third pass"): only when the flags ask for SanitizerCoverage
# (libFuzzer builds; clang warns about the option otherwise).
case " $CXXFLAGS " in
  *fuzzer-no-link* | *-fsanitize-coverage=*)
    ignore="-fsanitize-coverage-ignorelist=$PWD/fuzz/coverage-ignorelist.txt"
    CFLAGS="$CFLAGS $ignore"
    CXXFLAGS="$CXXFLAGS $ignore"
    ;;
esac

# CMAKE_BUILD_TYPE=None: no optimisation flags of our own on top of theirs.
cmake -S . -B build/oss -G Ninja \
  -DCMAKE_BUILD_TYPE=None \
  -DCMAKE_C_COMPILER="$CC" -DCMAKE_CXX_COMPILER="$CXX" \
  -DCMAKE_C_FLAGS="$CFLAGS" -DCMAKE_CXX_FLAGS="$CXXFLAGS" \
  -DTOPKIT_FUZZ=ON -DTOPKIT_FUZZ_ENGINE="$LIB_FUZZING_ENGINE" \
  -DTOPKIT_TESTS=OFF -DTOPKIT_TOOLS=ON -DTOPKIT_BENCH=OFF
cmake --build build/oss -j"$(nproc)" --target topkit_fuzz_all

cp build/oss/fuzz/top.dict "$OUT/top.dict"
for bin in build/oss/fuzz/fuzz_*; do
  [ -x "$bin" ] || continue
  t=$(basename "$bin")
  name=${t#fuzz_}
  cp "$bin" "$OUT/"
  cp build/oss/fuzz/top.dict "$OUT/$t.dict"
  if [ -f "fuzz/$t.options" ]; then
    cp "fuzz/$t.options" "$OUT/$t.options"
  fi
  seeds=()
  for d in "fuzz/corpus/$name" "fuzz/regressions/$name"; do
    [ -d "$d" ] && seeds+=("$d")
  done
  if [ ${#seeds[@]} -gt 0 ]; then
    rm -f "$OUT/${t}_seed_corpus.zip"
    find "${seeds[@]}" -type f -print0 | xargs -0 zip -q -j "$OUT/${t}_seed_corpus.zip"
  fi
done
