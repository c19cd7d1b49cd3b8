#!/usr/bin/env bash
# Transcribes the PixEagle gimbal bench's UDP sessions into pcaps (README.md).
# Usage: captures/sip-bench/transcribe.sh EVIDENCE_DIR [BUILD_DIR]
#   EVIDENCE_DIR holds <session>/events.jsonl as in alireza787b/PixEagle @
#   3bea324, docs/reporting/agent-ops/codex-modernization/evidence/
#   2026-09-17-gimbal-control-bench/; each file's sha256 must be the one its
#   manifest.json lists (sessions.txt here repeats them).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
evidence="${1:?usage: transcribe.sh EVIDENCE_DIR [BUILD_DIR]}"
build="${2:-$here/../../build/default}"
conv="$build/analyzer/bench_to_pcap"
[ -x "$conv" ] || { echo "transcribe: $conv is not built" >&2; exit 2; }
grep -v '^#' "$here/sessions.txt" | while read -r session sha _; do
  [ -n "$session" ] || continue
  events="$evidence/$session/events.jsonl"
  got=$(sha256sum "$events" | cut -d' ' -f1)
  if [ "$got" != "$sha" ]; then
    echo "transcribe: $events: sha256 $got, the manifest says $sha" >&2
    exit 2
  fi
  "$conv" "$events" "$here/$session.pcap"
done
