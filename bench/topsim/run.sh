#!/usr/bin/env bash
# topsim and topconf figures: requests/s over UDP loopback with lost
# responses (against a UDP echo floor measured in the same run), and the
# wall time of each model's default matrix against topsim, in process and
# over UDP. Targets: >= 10000 requests/s with 0 lost; a matrix < 10 s.
#
#   bench/topsim/run.sh [BUILD_DIR]      (default build/default)
set -euo pipefail
cd "$(dirname "$0")/../.."
B=${1:-build/default}/conformance
L=${1:-build/default}/bench
for exe in $B/topsim $B/topconf $L/topsim_load; do
  [ -x "$exe" ] || { echo "run.sh: $exe missing; build the default preset first" >&2; exit 2; }
done
status=0
echo "== topsim requests/s over UDP loopback (200000 requests, 32 in flight)"
for m in c12 sip; do
  "$L/topsim_load" --model "$m" --requests 200000 --window 32 || status=1
done
echo
echo "== default matrix wall time (target < 10 s)"
printf '%-8s %-12s %8s %s\n' model target seconds result
for m in $("$B/topconf" models); do
  t0=$(date +%s.%N)
  rc=0; "$B/topconf" run --model "$m" -q >/dev/null || rc=$?
  t1=$(date +%s.%N)
  s=$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.2f", b-a}')
  printf '%-8s %-12s %8.2f %s\n' "$m" in-process "$s" "exit $rc"
  [ "$rc" = 0 ] && awk -v s="$s" 'BEGIN{exit !(s < 10)}' || status=1

  out=$(mktemp)
  "$B/topsim" --model "$m" --udp 127.0.0.1:0 --reply-port 0 >"$out" 2>/dev/null &
  pid=$!
  for _ in $(seq 50); do [ -s "$out" ] && break; sleep 0.05; done
  port=$(awk '{split($2,a,":"); print a[2]}' "$out")
  t0=$(date +%s.%N)
  rc=0; "$B/topconf" run --model "$m" --target "udp://127.0.0.1:$port" --bind 0 -q >/dev/null || rc=$?
  t1=$(date +%s.%N)
  kill "$pid"; wait "$pid" 2>/dev/null || true
  rm -f "$out"
  s=$(awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.2f", b-a}')
  printf '%-8s %-12s %8.2f %s\n' "$m" udp "$s" "exit $rc"
  [ "$rc" = 0 ] && awk -v s="$s" 'BEGIN{exit !(s < 10)}' || status=1
done
exit $status
