#!/usr/bin/env bash
# The repository's commit-msg hook (.githooks/commit-msg) takes a subject of 72 characters and
# refuses one of 73, and refuses a body that starts without a blank line.
set -euo pipefail
hook="$(dirname "$0")/../../.githooks/commit-msg"
msg=$(mktemp)
trap 'rm -f "$msg"' EXIT
printf '%s\n\nbody\n' "$(printf 'a%.0s' $(seq 72))" > "$msg"
"$hook" "$msg" || { echo "FAIL: a 72-character subject was refused"; exit 1; }
printf '%s\n' "$(printf 'a%.0s' $(seq 73))" > "$msg"
if "$hook" "$msg" 2> /dev/null; then echo "FAIL: a 73-character subject was taken"; exit 1; fi
printf 'Subject\nbody at once\n' > "$msg"
if "$hook" "$msg" 2> /dev/null; then echo "FAIL: a body without a blank line was taken"; exit 1; fi
printf '# a comment git strips\nSubject\n' > "$msg"
"$hook" "$msg" || { echo "FAIL: git's comment lines were read as the subject"; exit 1; }
echo "commit-msg hook: 72 characters taken, 73 refused"
