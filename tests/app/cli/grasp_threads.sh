#!/usr/bin/env bash
# grasp_threads.sh TOPOPLAN DIR: `grasp transfer` of one grasp with every method and one perturbed
# repetition, once with 1 thread and once with 2; the report.json files must be byte-identical but
# for their provenance (the command lines differ).
set -u
bin=$1 out=$2
rm -rf "$out"
for n in 1 2; do
  "$bin" grasp transfer --grasp lateral_pinch_box --method all --repeats 1 --seed 5 --threads "$n" \
    -o "$out/t$n" 2>"$out.t$n.log" >/dev/null
  rc=$?
  [[ $rc -le 1 ]] || { echo "grasp_threads.sh: --threads $n exited $rc"; cat "$out.t$n.log"; exit 1; }
done
for n in 1 2; do grep -v '"command":' "$out/t$n/report.json" >"$out/t$n.cmp"; done
cmp "$out/t1.cmp" "$out/t2.cmp" || { echo "reports differ"; exit 1; }
grep -q '"perturbed"' "$out/t1/report.json" || { echo "no perturbed entries"; exit 1; }
exit 0
