#!/usr/bin/env bash
# interrupt_grasp.sh SIGNAL TOPOPLAN DIR: sends SIGNAL to `topoplan grasp transfer` (8 grasps,
# human reference) once its first grasp has finished and checks that it exits with 130, that
# DIR/report.json says "interrupted" and holds the finished grasps only (1..7), and that no staging
# folder is left.
set -u
sig=$1 bin=$2 out=$3
log=$out.log
rm -rf "$out" "$out".partial-* "$log"
"$bin" grasp transfer --method human --threads 1 -o "$out" 2>"$log" >/dev/null &
pid=$!
for _ in $(seq 1 1200); do  # at most 120 s for the first grasp
  grep -q '^grasp ' "$log" 2>/dev/null && break
  sleep 0.1
done
kill -"$sig" "$pid"
wait "$pid"
rc=$?
fail() { echo "interrupt_grasp.sh: $*"; cat "$log"; exit 1; }
[[ $rc -eq 130 ]] || fail "expected exit 130 after SIG$sig, got $rc"
[[ -f "$out/report.json" ]] || fail "no report.json"
grep -q '"status": "interrupted"' "$out/report.json" || fail "report.json does not say interrupted"
grasps=$(grep -c '"file":' "$out/report.json")
[[ $grasps -ge 1 && $grasps -lt 8 ]] || fail "expected 1..7 finished grasps, got $grasps"
[[ -f "$out/summary.md" ]] || fail "no summary.md"
compgen -G "$out.partial-*" >/dev/null && fail "staging folder left behind"
grep -q "interrupted: wrote" "$log" || fail "no 'interrupted' message"
exit 0
