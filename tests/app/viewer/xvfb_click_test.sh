#!/usr/bin/env bash
# The real window under Xvfb: open `topoplan view`, click the "chains" checkbox with xdotool (X
# input, not a script), and check that the window's pixels changed. Run inside xvfb-run:
#   xvfb-run -a -s "-screen 0 1280x720x24" xvfb_click_test.sh TOPOPLAN OUT_DIR
set -euo pipefail
bin=$1
out=$2
mkdir -p "$out"
rm -f "$out"/before.png "$out"/after.png

# Widget rectangles come from the headless twin: the same panels at the same size.
read -r x y < <("$bin" view unwrap --headless --print-widgets --size 1280x720 |
  awk '$1 == "widget" && $2 == "chains" { printf "%d %d\n", ($3 + $5) / 2, ($4 + $6) / 2 }')
echo "chains checkbox at $x,$y"

# Wait until the X server answers, then open the window; if the viewer exits before its window
# appears (seen once in CI: "GLFW: cannot initialise" from an X server that did not answer on a
# loaded machine), start it again, at most 3 times. The pass condition below is unchanged.
for _ in $(seq 50); do
  xdotool getdisplaygeometry >/dev/null 2>&1 && break
  sleep 0.2
done
pid=
trap '[[ -n "$pid" ]] && kill $pid 2>/dev/null || true' EXIT
for attempt in 1 2 3; do
  "$bin" view unwrap --size 1280x720 --exit-after 100000 &
  pid=$!
  shown=0
  for _ in $(seq 100); do
    if xdotool search --name '^topoplan$' >/dev/null 2>&1; then
      shown=1
      break
    fi
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.2
  done
  [[ $shown == 1 ]] && break
  wait "$pid" 2>/dev/null || true
  echo "the viewer's window did not appear (attempt $attempt)"
  sleep 1
done
if [[ $shown != 1 ]]; then
  echo "FAIL: the viewer's window did not appear in 3 attempts"
  exit 1
fi
sleep 2  # let it draw a few frames
import -window root "$out/before.png"
xdotool mousemove "$x" "$y" click 1
sleep 2
import -window root "$out/after.png"
kill "$pid"
wait "$pid" 2>/dev/null || true
trap - EXIT

# `topoplan diff` exits 1 when the images differ: that is the pass condition here.
set +e
"$bin" diff "$out/before.png" "$out/after.png" -o "$out/diff.png"
rc=$?
set -e
if [[ $rc -ne 1 ]]; then
  echo "FAIL: clicking 'chains' did not change the window (diff exit $rc)"
  exit 1
fi
echo "PASS: the click changed the window"
