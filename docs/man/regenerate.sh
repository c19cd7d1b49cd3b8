#!/usr/bin/env bash
# Regenerates docs/man/*.1 from the tools' --help (tools/man/man_page.cmake).
# Usage: docs/man/regenerate.sh [BUILD_DIR]   (default: build/default)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build/default}"
case "$build" in /*) ;; *) build="$root/$build" ;; esac
for tool in analyzer/topdump conformance/topsim conformance/topconf; do
  name="$(basename "$tool")"
  cmake -DTOOL="$build/$tool" -DOUT="$root/docs/man/$name.1" -P "$root/tools/man/man_page.cmake"
done
echo "man pages written to $root/docs/man"
