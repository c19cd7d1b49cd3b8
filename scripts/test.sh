#!/usr/bin/env bash
# The whole test suite, as CI runs it: install, build (default preset), run
# every test; then the same under ASan+UBSan; then a short libFuzzer run of
# every target when clang is available (fuzz/run-ci.sh, if present).
# Each phase's end is stamped with the seconds since the start, so a CI
# log says where its time went (CI must stay under 30 minutes).
set -euo pipefail
cd "$(dirname "$0")/.."
phase() { echo "test.sh: [${SECONDS} s] $*"; }
./scripts/install-deps.sh
phase "dependencies installed"
cmake --preset default
cmake --build --preset default
phase "default build done"
ctest --preset default
phase "default tests passed"
if [ "${TOPKIT_SKIP_ASAN:-0}" != 1 ]; then
  cmake --preset asan
  cmake --build --preset asan
  phase "asan build done"
  ctest --preset asan
  phase "asan tests passed"
fi
if [ -x fuzz/run-ci.sh ] && [ "${TOPKIT_SKIP_FUZZ:-0}" != 1 ]; then
  ./fuzz/run-ci.sh
  phase "fuzz run passed"
fi
phase "all passed"
