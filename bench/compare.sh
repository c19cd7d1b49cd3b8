#!/usr/bin/env bash
# Times two topdump builds against each other on the benchmark capture:
# `stats` and `read --json > /dev/null`, taking turns (A, B, B, A, ...) so
# that the host's drift falls on both, pinned to one core when taskset
# exists, the wall-clock time of each run. Prints each build's p10 and
# median per command and B's change against A. Run by hand (not in CI):
#   [ROUNDS=21] bench/compare.sh BUILD_A BUILD_B [FRAMES]   (default 1000000)
set -euo pipefail
a="${1:?usage: compare.sh BUILD_A BUILD_B [FRAMES]}"
b="${2:?usage: compare.sh BUILD_A BUILD_B [FRAMES]}"
frames="${3:-1000000}"
rounds="${ROUNDS:-21}"
for d in "$a" "$b"; do
  [ -x "$d/analyzer/topdump" ] || { echo "compare: $d/analyzer/topdump is not built" >&2; exit 2; }
done
pin=""
command -v taskset >/dev/null && pin="taskset -c 0"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
"$a/analyzer/gen_capture" "$frames" "$tmp/bench.pcap" 1 >/dev/null

# One run: wall-clock seconds (nanosecond clock; /usr/bin/time's CPU times
# step by 10 ms, 4% of a 1M-frame stats run).
cpu() {
  local t0 t1
  t0=$(date +%s%N)
  $pin "$@" >/dev/null 2>/dev/null || true
  t1=$(date +%s%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.4f\n", (b - a) / 1e9}'
}
for i in $(seq "$rounds"); do
  order="$a $b"
  [ $((i % 2)) = 0 ] && order="$b $a"
  for d in $order; do
    tag=$([ "$d" = "$a" ] && echo A || echo B)
    cpu "$d/analyzer/topdump" stats "$tmp/bench.pcap" >>"$tmp/stats.$tag"
    cpu "$d/analyzer/topdump" read --json "$tmp/bench.pcap" >>"$tmp/json.$tag"
  done
done
# p10 and median of a file of numbers
pct() { sort -n "$1" | awk -v q="$2" '{v[NR]=$1} END {i=int((NR-1)*q)+1; print v[i]}'; }
printf '%-6s %10s %10s %10s %10s %9s %9s\n' command A_p10 A_median B_p10 B_median d_p10 d_median
for c in stats json; do
  ap=$(pct "$tmp/$c.A" 0.1) am=$(pct "$tmp/$c.A" 0.5) bp=$(pct "$tmp/$c.B" 0.1) bm=$(pct "$tmp/$c.B" 0.5)
  awk -v c="$c" -v ap="$ap" -v am="$am" -v bp="$bp" -v bm="$bm" 'BEGIN{
    printf "%-6s %10.3f %10.3f %10.3f %10.3f %+8.1f%% %+8.1f%%\n", c, ap, am, bp, bm,
      (bp/ap-1)*100, (bm/am-1)*100 }'
done
echo "($rounds interleaved rounds, $frames frames, wall-clock seconds; A: $a, B: $b)"
