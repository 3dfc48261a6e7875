#!/usr/bin/env bash
# hostile_input.sh KIND READER TOPOPLAN
# Feeds one hostile file to one reader of `topoplan` and checks that it is refused quickly: exit 2
# within 10 s (the command is killed after 30 s), with a message naming the file.
#   KIND:   zero   (a link to /dev/zero: endless bytes)
#           fifo   (a named pipe nobody writes to: opening it for reading would block)
#           sparse (a 100 GB sparse file: no disk used, but endless to read)
#   READER: mesh_urdf  (a URDF <mesh> of the file; planning::LoadMesh)
#           mesh_scene (a render scene's "mesh" shape of the file; planning::LoadMesh)
#           robot_json (`check` of the file as a robot scene .json)
#           chain      (`writhe` of the file as a chain CSV)
#           view_json  (`view` of the file as a scenario or scene .json, headless)
set -u
kind=$1 reader=$2 topoplan=$3
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

case "$reader" in
  mesh_urdf | mesh_scene) name=hostile.stl ;;
  robot_json | view_json) name=hostile.json ;;
  chain) name=hostile.csv ;;
  *) echo "unknown reader $reader"; exit 1 ;;
esac
file=$dir/$name
case "$kind" in
  zero) ln -s /dev/zero "$file" ;;
  fifo) mkfifo "$file" ;;
  sparse) truncate -s 100G "$file" ;;
  *) echo "unknown kind $kind"; exit 1 ;;
esac

case "$reader" in
  mesh_urdf)
    cat >"$dir/robot.urdf" <<EOF
<?xml version="1.0"?>
<robot name="hostile">
  <link name="base">
    <collision><geometry><mesh filename="$name"/></geometry></collision>
  </link>
</robot>
EOF
    cmd=("$topoplan" check "$dir/robot.urdf") ;;
  mesh_scene)
    echo "{\"shapes\": [{\"type\": \"mesh\", \"file\": \"$name\"}]}" >"$dir/scene.json"
    cmd=("$topoplan" render "$dir/scene.json" -o "$dir/out.png") ;;
  robot_json) cmd=("$topoplan" check "$file") ;;
  view_json) cmd=("$topoplan" view "$file" --screenshot "$dir/out.png") ;;
  chain)
    printf '0,0,0\n1,0,0\n1,1,0\n' >"$dir/b.csv"
    cmd=("$topoplan" writhe "$file" "$dir/b.csv") ;;
esac

start=$(date +%s%N)
out=$(timeout 30 "${cmd[@]}" 2>&1)
rc=$?
ms=$((($(date +%s%N) - start) / 1000000))
echo "$kind $reader: exit $rc after $ms ms: $out"
[[ $rc -eq 2 ]] || { echo "FAIL: expected exit 2"; exit 1; }
grep -q -- "$name" <<<"$out" || { echo "FAIL: the message does not name $name"; exit 1; }
[[ $ms -lt 10000 ]] || { echo "FAIL: took $ms ms (limit 10 s)"; exit 1; }
[[ -e "$dir/out.png" ]] && { echo "FAIL: wrote an output"; exit 1; }
exit 0
