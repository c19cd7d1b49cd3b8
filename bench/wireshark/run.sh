#!/usr/bin/env bash
# tshark with the generated dissector (BUILD_DIR/analyzer/top.lua) against the
# hand-written framing-only one (bench/wireshark/framing.lua) and against
# tshark without any TOP dissector, on the benchmark capture of
# bench/gen_capture.cpp. Prints, for the run with the least CPU time
# (user+sys) of ROUNDS runs of each, one after the other, pinned to one core,
# its CPU and wall-clock seconds, for two outputs: the one-line summaries
# (`tshark -r`) and the whole tree (`tshark -V`). CPU time, because on a
# shared machine the wall clock says more about the neighbours.
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

best() {  # "cpu wall": the run with the least CPU time (user+sys) of $rounds runs of "$@"
  local b="" bw=""
  for _ in $(seq "$rounds"); do
    /usr/bin/time -f "%U %S %e" -o "$tmp/time" $pin "$@" >/dev/null 2>/dev/null
    local u s e c
    read -r u s e < <(tail -1 "$tmp/time")
    c=$(awk "BEGIN{printf \"%.2f\", $u + $s}")
    if [ -z "$b" ] || awk "BEGIN{exit !($c < $b)}"; then b=$c; bw=$e; fi
  done
  echo "$b $bw"
}

tshark -v 2>/dev/null | head -1
echo "capture: $frames frames, $(stat -c %s "$cap") bytes; best of $rounds by CPU time (user+sys), seconds"
printf '%-12s %12s %12s %12s %12s\n' dissector summary_cpu summary_wall tree_cpu tree_wall
for what in none framing generated; do
  case $what in
    none) lua=() ;;
    framing) lua=(-X "lua_script:$root/bench/wireshark/framing.lua") ;;
    generated) lua=(-X "lua_script:$build/analyzer/top.lua") ;;
  esac
  read -r sc sw < <(best tshark -n "${lua[@]}" -r "$cap")
  read -r vc vw < <(best tshark -n -V "${lua[@]}" -r "$cap")
  printf '%-12s %12s %12s %12s %12s\n' "$what" "$sc" "$sw" "$vc" "$vw"
done
