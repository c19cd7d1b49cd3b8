#!/usr/bin/env bash
# tshark with the generated dissector (tools/wireshark/top.lua) against the
# hand-written framing-only one (bench/wireshark/framing.lua) and against
# tshark without any TOP dissector, on the benchmark capture of
# bench/gen_capture.cpp. Prints the best wall-clock time of ROUNDS runs of
# each, one after the other, pinned to one core, for two outputs: the one-line
# summaries (`tshark -r`) and the whole tree (`tshark -V`).
#   bench/wireshark/run.sh [BUILD_DIR] [FRAMES] [ROUNDS]
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
build="${1:-$root/build/default}"
frames="${2:-100000}"
rounds="${3:-3}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
cap="$tmp/bench.pcap"
"$build/analyzer/gen_capture" "$frames" "$cap" >/dev/null
pin=""
if command -v taskset >/dev/null; then pin="taskset -c 0"; fi

best() {  # best wall-clock seconds of $rounds runs of "$@"
  local b=""
  for _ in $(seq "$rounds"); do
    local t
    t=$( { /usr/bin/time -f %e $pin "$@" >/dev/null 2>/dev/null; } 2>&1 | tail -1)
    if [ -z "$b" ] || awk "BEGIN{exit !($t < $b)}"; then b=$t; fi
  done
  echo "$b"
}

tshark -v 2>/dev/null | head -1
echo "capture: $frames frames, $(stat -c %s "$cap") bytes; best of $rounds"
printf '%-22s %10s %10s\n' dissector "summary_s" "tree_s"
for what in none framing generated; do
  case $what in
    none) lua=() ;;
    framing) lua=(-X "lua_script:$root/bench/wireshark/framing.lua") ;;
    generated) lua=(-X "lua_script:$root/tools/wireshark/top.lua") ;;
  esac
  s=$(best tshark -n "${lua[@]}" -r "$cap")
  v=$(best tshark -n -V "${lua[@]}" -r "$cap")
  printf '%-22s %10s %10s\n' "$what" "$s" "$v"
done
