#!/usr/bin/env bash
# Regenerates captures/golden/* from the current topdump (review the diff!).
# Usage: captures/update-golden.sh [BUILD_DIR]   (default: build/default)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/default}"
case "$build" in /*) ;; *) build="$root/$build" ;; esac
topdump="$build/analyzer/topdump"
cd "$root/captures"
grep -v '^#' golden/cases.txt | while read -r name args; do
  [ -n "$name" ] || continue
  set +e
  # shellcheck disable=SC2086
  "$topdump" $args >golden/.out 2>golden/.err </dev/null
  rc=$?
  set -e
  { cat golden/.out; echo "-- stderr"; cat golden/.err; echo "-- exit $rc"; } >"golden/$name"
done
rm -f golden/.out golden/.err
echo "goldens written to $root/captures/golden"
