#!/usr/bin/env bash
# interrupt.sh SIGNAL TOPOPLAN DIR: sends SIGNAL to `topoplan bench unwrap` (10 runs) once its
# first run has finished and checks that it exits with 130, that DIR/unwrap.partial.csv holds the
# header and the finished rows only, and that no unwrap.csv / unwrap.png (the names of a complete
# sweep) and no staging folder are left.
set -u
sig=$1 bin=$2 out=$3
log=$out.log
rm -rf "$out" "$out".partial-* "$log"
"$bin" bench unwrap --angles 0:360:90 --seeds 2 --planners birrt -o "$out" 2>"$log" >/dev/null &
pid=$!
for _ in $(seq 1 600); do  # at most 60 s for the first run
  grep -Eq '\] [1-9]/10' "$log" 2>/dev/null && break
  sleep 0.1
done
kill -"$sig" "$pid"
wait "$pid"
rc=$?
fail() { echo "interrupt.sh: $*"; cat "$log"; exit 1; }
[[ $rc -eq 130 ]] || fail "expected exit 130 after SIG$sig, got $rc"
[[ -f "$out/unwrap.partial.csv" ]] || fail "no unwrap.partial.csv"
[[ ! -e "$out/unwrap.csv" ]] || fail "unwrap.csv written for a partial sweep"
rows=$(($(wc -l <"$out/unwrap.partial.csv") - 1))
[[ $rows -ge 1 && $rows -lt 10 ]] || fail "expected 1..9 finished rows, got $rows"
head -1 "$out/unwrap.partial.csv" | grep -q '^angle_deg,planner,seed,success' || fail "bad header"
[[ ! -e "$out/unwrap.png" ]] || fail "unwrap.png of a partial sweep was written"
compgen -G "$out.partial-*" >/dev/null && fail "staging folder left behind"
grep -q "interrupted: wrote" "$log" || fail "no 'interrupted' message"
exit 0
