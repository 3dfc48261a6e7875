#!/usr/bin/env bash
# kill_resume_grasp.sh TOPOPLAN DIR: hard-kill resume of `bench grasp --quick`. Makes a clean
# run's grasp.csv in DIR.clean (the reference), then starts the run in DIR, sends SIGKILL once its
# journal holds at least 3 finished trials, appends a torn half line to the journal (a write cut
# short by a power loss), checks that a rerun with another protocol (--seed 1) is refused with
# exit 2 naming the journal and the setting that differs, then reruns the same command and checks
# that it resumes (it runs fewer than the 20 trials, the rest come from the journal), that its
# grasp.csv equals the clean run's byte for byte, and that no journal or staging folder is left.
set -u
bin=$1 out=$2
log=$out.log
journal=$out/.topoplan-journal-bench-grasp
reference=$out.clean/grasp.csv
rm -rf "$out" "$out.clean" "$log"
fail() { echo "kill_resume_grasp.sh: $*"; cat "$log" 2>/dev/null; exit 1; }
"$bin" bench grasp --quick -o "$out.clean" >/dev/null 2>"$log" || fail "the clean run failed"
[[ -f "$reference" ]] || fail "the clean run wrote no grasp.csv"

"$bin" bench grasp --quick -o "$out" >/dev/null 2>"$log" &
pid=$!
records=0
for _ in $(seq 1 3000); do  # at most 300 s
  if [[ -f "$journal" ]]; then
    records=$(($(grep -c $'\t' "$journal") + 0))
    [[ $records -ge 3 ]] && break
  fi
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
kill -KILL "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
[[ $records -ge 3 ]] || fail "the journal never held 3 trials"
[[ -f "$out/grasp.csv" ]] && fail "a killed run left a grasp.csv (it wrote outputs before the end)"
kept=$(grep -c $'\t' "$journal")
[[ $kept -lt 20 ]] || fail "the run finished before it could be killed ($kept trials)"
printf 'power_bottle,bottle,contr' >>"$journal"  # torn: no checksum, no newline

"$bin" bench grasp --quick --seed 1 -o "$out" >"$log" 2>&1
rc=$?
[[ $rc -eq 2 ]] || fail "a rerun with another protocol exited $rc, expected 2"
expected="another configuration (journal: 'seed=0'; this run: 'seed=1')"
grep -qF "journal-bench-grasp: was written by $expected" "$log" ||
  fail "the refusal does not name the journal"

"$bin" bench grasp --quick -o "$out" >"$log" 2>&1
rc=$?
[[ $rc -eq 0 ]] || fail "the resumed run exited $rc"
grep -q "dropped a torn last line" "$log" || fail "the torn line was not reported"
line=$(grep -o "[0-9]* trials run in .* ([0-9]* from an earlier run)" "$log") ||
  fail "no summary line"
ran=${line%% *}
earlier=$(echo "$line" | sed 's/.*(\([0-9]*\) from an earlier run)/\1/')
[[ $earlier -ge $kept && $ran -lt 20 && $((ran + earlier)) -eq 20 ]] ||
  fail "expected the resumed run to run 20 - $kept or fewer trials, got '$line'"
cmp "$out/grasp.csv" "$reference" || fail "grasp.csv differs from the clean run's"
[[ -e "$journal" ]] && fail "the journal was left behind"
compgen -G "$out/.topoplan-staging-*" >/dev/null && fail "a staging folder was left behind"
echo "killed after $kept journalled trials; resumed run ran $ran, kept $earlier; grasp.csv equal"
exit 0
