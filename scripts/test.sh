#!/usr/bin/env bash
# The whole test suite, as CI runs it: install, build (default preset), run
# every test; then the same under ASan+UBSan; then a short libFuzzer run of
# every target when clang is available (fuzz/run-ci.sh, if present).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install-deps.sh
cmake --preset default
cmake --build --preset default
ctest --preset default
if [ "${TOPKIT_SKIP_ASAN:-0}" != 1 ]; then
  cmake --preset asan
  cmake --build --preset asan
  ctest --preset asan
fi
if [ -x fuzz/run-ci.sh ] && [ "${TOPKIT_SKIP_FUZZ:-0}" != 1 ]; then
  ./fuzz/run-ci.sh
fi
echo "test.sh: all passed"
