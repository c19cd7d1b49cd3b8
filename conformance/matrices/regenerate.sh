#!/usr/bin/env bash
# Regenerates the default matrices and the schema's model list from the
# catalog (run after the catalog changes, e.g. after `git merge main`), then
# review the diff:
#   conformance/matrices/regenerate.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
topconf=${1:-build/default}/conformance/topconf
# the schema's model list, from the library's
models=$("$topconf" models | sed 's/.*/"&"/' | paste -sd, - | sed 's/,/, /g')
sed -i "s/^    \"model\": {\"enum\": \[.*\]},\$/    \"model\": {\"enum\": [$models]},/" conformance/matrix.schema.json
for m in $("$topconf" models); do
  "$topconf" generate --model "$m" -o "conformance/matrices/$m.json"
  "$topconf" validate "conformance/matrices/$m.json"
done
