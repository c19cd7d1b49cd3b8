#!/usr/bin/env bash
# Times topdump against the libpcap read floor, in the same run, and prints
# the ratios and peak memory. Run by hand (not in CI):
#   [ROUNDS=5] bench/run.sh [BUILD_DIR] [FRAMES]   (defaults: build/default, 1000000)
# Generates FRAMES-frame and 4xFRAMES-frame captures in a temporary
# directory, then for each: the floor `tcpdump -r FILE -w /dev/null`,
# `topdump stats FILE`, `topdump read --json FILE > /dev/null` and
# `topdump report FILE -o report.html` (its time against stats, and the
# page's size: targets 3x and 5 MB, docs/REPORT.md), taking
# turns ROUNDS times, each the best of its wall-clock runs (date +%s.%N
# around /usr/bin/time), pinned to one core when taskset exists; peak RSS
# from /usr/bin/time -v.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/default}"
frames="${2:-1000000}"
rounds="${ROUNDS:-5}"
topdump="$build/analyzer/topdump"
gen="$build/analyzer/gen_capture"
for tool in tcpdump /usr/bin/time; do
  command -v "$tool" >/dev/null || { echo "bench: $tool missing (scripts/install-deps.sh)"; exit 2; }
done
pin=""
command -v taskset >/dev/null && pin="taskset -c 0"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# One run: wall-clock seconds and peak RSS (KiB).
once() {
  local t0 t1
  t0=$(date +%s.%N)
  /usr/bin/time -v -o "$tmp/time" $pin "$@" >/dev/null 2>"$tmp/err" || true
  t1=$(date +%s.%N)
  awk -v a="$t0" -v b="$t1" 'BEGIN{printf "%.4f ", b-a}'
  awk -F': ' '/Maximum resident set size/ {print $2}' "$tmp/time"
}
min() { awk -v a="$1" -v b="$2" 'BEGIN{print (a == "" || b < a) ? b : a}'; }

# whether the build is profile-guided (cmake/pgo.cmake): say which is timed
pgo=$(awk -F= '/^TOPKIT_PGO:/ {print $2}' "$build/CMakeCache.txt" 2>/dev/null || true)
echo "topdump: $topdump (TOPKIT_PGO=${pgo:-unknown})"
printf '%-8s %10s %10s %10s %10s %8s %8s %12s %10s %10s %9s %7s %8s\n' capture frames floor_s stats_s \
  json_s stats/fl json/fl json_fr/s rss_stats rss_json report_s rep/st rep_MB
for mult in 1 4; do
  n=$((frames * mult))
  f="$tmp/bench-$mult.pcap"
  "$gen" "$n" "$f" 1 >/dev/null
  # the commands take turns, ROUNDS times, and each keeps its best:
  # on a shared VM the speed drifts within minutes, and a floor measured
  # minutes apart from what it is compared with misleads
  floor="" st="" js="" rp=""
  for _ in $(seq "$rounds"); do
    read -r t _ < <(once tcpdump -r "$f" -w /dev/null)
    floor=$(min "$floor" "$t")
    read -r t st_rss < <(once "$topdump" stats "$f")
    st=$(min "$st" "$t")
    read -r t js_rss < <(once "$topdump" read --json "$f")
    js=$(min "$js" "$t")
    read -r t _ < <(once "$topdump" report "$f" -o "$tmp/report.html")
    rp=$(min "$rp" "$t")
  done
  rp_size=$(stat -c %s "$tmp/report.html")
  got=$({ "$topdump" stats --json "$f" 2>/dev/null || true; } | awk -F': ' '/^  "frames"/ {gsub(",","",$2); print $2}')
  awk -v c="${mult}x" -v n="$got" -v fl="$floor" -v st="$st" -v js="$js" -v r1="$st_rss" -v r2="$js_rss" \
    -v rp="$rp" -v rs="$rp_size" 'BEGIN{
    printf "%-8s %10d %10.3f %10.3f %10.3f %8.2f %8.2f %12.0f %8.1fMB %8.1fMB %9.3f %7.2f %8.2f\n",
      c, n, fl, st, js, st/fl, js/fl, n/js, r1/1024, r2/1024, rp, rp/st, rs/1048576 }'
done
echo "(targets: stats/fl <= 2, json frames/s >= 1000000, RSS flat from 1x to 4x, rep/st <= 3, rep_MB <= 5)"
