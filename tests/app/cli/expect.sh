#!/usr/bin/env bash
# expect.sh RC PATTERN -- COMMAND...
# Runs COMMAND, fails unless it exits with RC and its stdout+stderr match the extended regex
# PATTERN (an empty PATTERN matches anything).
set -u
want_rc=$1 pattern=$2
shift 2
[[ "$1" == "--" ]] && shift
out=$("$@" 2>&1)
rc=$?
if [[ $rc -ne $want_rc ]]; then
  echo "expected exit $want_rc, got $rc from: $*"; echo "$out"; exit 1
fi
if [[ -n "$pattern" ]] && ! grep -Eq -- "$pattern" <<<"$out"; then
  echo "output does not match /$pattern/: $*"; echo "$out"; exit 1
fi
exit 0
