# Inputs of the robustness check that were still accepted wrongly (included by
# tests/app/cli/CMakeLists.txt).
# Optional output flags given as "" are refused (exit 2) instead of being ignored: `diff -o ""`,
# `writhe --heatmap ""`, `grasp synthesize -o ""`, `bench unwrap --ompl-log ""` and
# `view --screenshot ""` (which opened a window); `grasp synthesize -o` and `view --screenshot` are
# checked before the work.
set(GALLERY ${PROJECT_SOURCE_DIR}/docs/gallery/hopf_heatmap.png)
set(SPEC ${PROJECT_SOURCE_DIR}/assets/grasps/specs/power_bottle.json)
topoplan_empty_output_test(diff -o "diff ${GALLERY} ${GALLERY}")
topoplan_empty_output_test(writhe --heatmap "writhe ${CHAINS}/hopf_a.csv ${CHAINS}/hopf_b.csv")
topoplan_empty_output_test(synthesize -o "grasp synthesize ${SPEC}")
topoplan_empty_output_test(ompl_log --ompl-log "bench unwrap --angles 0:0:15 --planners birrt -o ${CLI_TMP}/empty_ompl_log")
topoplan_empty_output_test(view_screenshot --screenshot "view unwrap")
topoplan_cli_test(limit_view_unusable_screenshot 2 "--screenshot: '/dev/null/x.png': /dev/null is not a folder"
                  view unwrap --screenshot /dev/null/x.png)
topoplan_cli_test(limit_synthesize_unusable_output 2 "-o: '/dev/null/g.json': /dev/null is not a folder"
                  grasp synthesize ${SPEC} -o /dev/null/g.json)
# A re-plan period longer than the plan means no re-plan within it (1e300 s overflowed lround and
# became one slice: re-planning every slice).
topoplan_cli_test(limit_replan_period_huge 0 "re-planning: 0 re-plans every 4\\.000 s"
                  plan reach_through_ring --moving-object ring
                  --object-path ${PROJECT_SOURCE_DIR}/assets/scenarios/ring_path.csv
                  --replan-period 1e300 -o ${CLI_TMP}/replan_huge)

# Issue 40's classes, one test each (docs/robustness.md lists them with what happened before).
set(CLASS_TMP ${CMAKE_CURRENT_BINARY_DIR}/classes)
file(MAKE_DIRECTORY ${CLASS_TMP})
# Outputs that must never be replaced: a device node, a named pipe, an input of the same run, a
# folder of files topoplan did not write.
topoplan_cli_test(class_output_device 2 "-o: '/dev/null' is a device node"
                  render ${SCENES}/example.json -o /dev/null)
topoplan_cli_test(class_output_is_input 2 "-o: '.*example\\.json' is an input of this run"
                  render ${SCENES}/example.json -o ${SCENES}/example.json)
file(MAKE_DIRECTORY ${CLASS_TMP}/foreign)
file(WRITE ${CLASS_TMP}/foreign/thesis.tex "not ours\n")
topoplan_cli_test(class_output_foreign_folder 2 "holds files topoplan did not write \\('thesis\\.tex'"
                  plan reach_through_ring -o ${CLASS_TMP}/foreign)
add_test(NAME cli.class_output_fifo
         COMMAND sh -c "rm -f \"$1\" && mkfifo \"$1\" && \"$0\" render \"$2\" -o \"$1\" 2>&1 | grep -q 'is a named pipe' && test -p \"$1\""
                 $<TARGET_FILE:topoplan> ${CLASS_TMP}/pipe.png ${SCENES}/example.json)
set_tests_properties(cli.class_output_fifo PROPERTIES LABELS unit)
# Names taken from input files never leave -o.
file(READ ${PROJECT_SOURCE_DIR}/assets/grasps/power_bottle.json POWER_BOTTLE)
string(REGEX REPLACE "\"name\": *\"[^\"]*\"" "\"name\": \"../../escape\"" EVIL_GRASP "${POWER_BOTTLE}")
file(WRITE ${CLASS_TMP}/evil_grasp.json "${EVIL_GRASP}")
topoplan_cli_test(class_grasp_name_path 2 "evil_grasp\\.json: name: '\\.\\./\\.\\./escape' cannot be a file name"
                  grasp transfer --grasp ${CLASS_TMP}/evil_grasp.json -o ${CLASS_TMP}/evil_out)
# Strict readers: duplicate JSON keys, integers that look octal, empty integers, XML after its end.
file(WRITE ${CLASS_TMP}/dup.json "{\"shapes\": [], \"shapes\": [{\"type\": \"sphere\"}]}\n")
topoplan_cli_test(class_json_duplicate_key 2 "dup\\.json: \\(root\\): duplicate key 'shapes'"
                  render ${CLASS_TMP}/dup.json -o ${CLASS_TMP}/dup.png)
topoplan_cli_test(class_octal_seed 0 "\"seed\": 10,"
                  plan reach_through_ring --planner rrt --seed 010 --json -o ${CLASS_TMP}/octal)
add_test(NAME cli.class_empty_integer
         COMMAND sh -c "\"$0\" plan reach_through_ring --seed '' -o \"$1\" 2>&1 | grep -q \"seed: '' is not a whole decimal number\""
                 $<TARGET_FILE:topoplan> ${CLASS_TMP}/empty_int)
set_tests_properties(cli.class_empty_integer PROPERTIES LABELS unit)
file(WRITE ${CLASS_TMP}/tail.urdf "<robot name=\"t\"><link name=\"a\"/></robot>\ngarbage\n")
topoplan_cli_test(class_xml_trailing_text 2 "tail\\.urdf:2: text after the document's element"
                  fk ${CLASS_TMP}/tail.urdf)
file(WRITE ${CLASS_TMP}/posed.json "{\"robot\": \"${PROJECT_SOURCE_DIR}/assets/robots/lwr4_sdh.urdf\", \"objects\": [{\"urdf\": \"${PROJECT_SOURCE_DIR}/assets/objects/box.urdf\", \"postion\": [0.7, 0, 0.3]}]}\n")
topoplan_cli_test(class_json_unknown_key 2 "posed\\.json: objects\\[0\\]\\.postion: unknown key 'postion' \\(did you mean 'position'\\?\\)"
                  check ${CLASS_TMP}/posed.json)
# A COLLADA file whose nodes instance each other in a cycle (crashed assimp).
file(WRITE ${CLASS_TMP}/cycle.dae "<?xml version=\"1.0\"?>\n<COLLADA xmlns=\"http://www.collada.org/2005/11/COLLADASchema\" version=\"1.4.1\">\n<library_nodes><node id=\"a\"><instance_node url=\"#b\"/></node><node id=\"b\"><instance_node url=\"#a\"/></node></library_nodes>\n<library_visual_scenes><visual_scene id=\"s\"><node id=\"r\"><instance_node url=\"#a\"/></node></visual_scene></library_visual_scenes>\n<scene><instance_visual_scene url=\"#s\"/></scene>\n</COLLADA>\n")
file(WRITE ${CLASS_TMP}/cycle.urdf "<robot name=\"c\"><link name=\"a\"><visual><geometry><mesh filename=\"cycle.dae\"/></geometry></visual></link></robot>\n")
topoplan_cli_test(class_collada_cycle 2 "COLLADA node 'a' instances itself \\('a' -> 'b' -> 'a'\\)"
                  fk ${CLASS_TMP}/cycle.urdf)
# Every write is checked, standard output too.
add_test(NAME cli.class_full_stdout
         COMMAND sh -c "\"$0\" writhe \"$1\" \"$2\" --json --total >/dev/full 2>\"$3\"; rc=$?; test $rc -eq 3 && grep -q 'No space left on device (ENOSPC)' \"$3\""
                 $<TARGET_FILE:topoplan> ${CHAINS}/hopf_a.csv ${CHAINS}/hopf_b.csv ${CLASS_TMP}/full.log)
set_tests_properties(cli.class_full_stdout PROPERTIES LABELS unit)
# A bogus GL driver setting is an environment error naming the variable (crashed OSMesa).
topoplan_cli_test(class_gallium_driver 3 "GALLIUM_DRIVER='nonsense'"
                  render ${SCENES}/example.json -o ${CLASS_TMP}/driver.png)
set_tests_properties(cli.class_gallium_driver PROPERTIES ENVIRONMENT "GALLIUM_DRIVER=nonsense")
# Messages: a NUL byte does not cut a message; view without a display says what to do.
topoplan_cli_test(class_view_no_display 3 "--screenshot out\\.png.*xvfb-run"
                  view unwrap)
set_tests_properties(cli.class_view_no_display PROPERTIES ENVIRONMENT "DISPLAY=")

# Inputs of the black-box review that were accepted silently; each is refused with exit 2, a
# message naming the file and key (or the flag), and no output written.
# topoplan_refused_test(name PATTERN args...): `topoplan args...`, with OUT in args replaced by a
# path of this test, exits 2 with PATTERN in its output and nothing named OUT* exists afterwards.
# Arguments go through sh, so "" stays one.
function(topoplan_refused_test name pattern)
  set(out ${CLASS_TMP}/refused_${name})
  set(cmd "")
  foreach(arg IN LISTS ARGN)
    string(REPLACE OUT "${out}" arg "${arg}")
    string(APPEND cmd " '${arg}'")
  endforeach()
  add_test(NAME cli.refused_${name}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "${pattern}" --
                   sh -c "rm -rf '${out}'*; \"$0\"${cmd}; rc=$?; if ls -d '${out}'* 2>/dev/null; then exit 9; fi; exit $rc"
                   $<TARGET_FILE:topoplan>)
  set_tests_properties(cli.refused_${name} PROPERTIES LABELS unit TIMEOUT 120)
endfunction()
# Flags given as "" meant their default; now "FLAG: empty value".
foreach(flag budget planners pole-offset scenario)
  topoplan_refused_test(empty_${flag} "--${flag}: empty value"
                        bench unwrap --angles 0:0:15 --${flag} "" -o OUT)
endforeach()
topoplan_refused_test(empty_plan_srdf "--srdf: empty value" plan unwrap --srdf "" -o OUT)
topoplan_refused_test(empty_plan_moving "--moving-object: empty value"
                      plan reach_through_ring --moving-object "" --object-path "" -o OUT)
topoplan_refused_test(empty_render_size "--size: empty value"
                      render ${SCENES}/example.json --size "" -o OUT.png)
topoplan_refused_test(empty_grasp_mu "--mu: empty value"
                      grasp transfer --grasp large_diameter_can --mu "" -o OUT)
# Unwrap geometries: the name is geometry.csv's first column (letters, digits, _ - . only), from
# "name" or the file's stem; disabled_groups prefixes must each start a link's name.
file(WRITE ${CLASS_TMP}/geo_name.json "{\"name\": \"a,b\\\"c\\nd\"}\n")
file(WRITE ${CLASS_TMP}/geo_empty_name.json "{\"name\": \"\"}\n")
file(WRITE ${CLASS_TMP}/geo,stem.json "{}\n")
set(ARM12 ${PROJECT_SOURCE_DIR}/assets/robots/arm12_sdh.urdf)
file(WRITE ${CLASS_TMP}/geo_prefix.json
     "{\"arm\": {\"urdf\": \"${ARM12}\", \"disabled_groups\": [[\"nonexistent_prefix_\"]]}}\n")
file(WRITE ${CLASS_TMP}/geo_empty_prefix.json
     "{\"arm\": {\"urdf\": \"${ARM12}\", \"disabled_groups\": [[\"sdh_\", \"\"]]}}\n")
set(GEO_RUN --angles 540:540:180 --seeds 1 --planners aico -o OUT)
topoplan_refused_test(geometry_name "geo_name\\.json: name: 'a,b\"c\\?d' holds ','"
                      bench unwrap --geometry ${CLASS_TMP}/geo_name.json ${GEO_RUN})
topoplan_refused_test(geometry_empty_name "geo_empty_name\\.json: name: is empty"
                      bench unwrap --geometry ${CLASS_TMP}/geo_empty_name.json ${GEO_RUN})
topoplan_refused_test(geometry_stem "geo,stem\\.json: name: the file's stem \\(the default name\\) 'geo,stem' holds ','"
                      bench unwrap --geometry ${CLASS_TMP}/geo,stem.json ${GEO_RUN})
topoplan_refused_test(geometry_prefix "geo_prefix\\.json: arm\\.disabled_groups\\[0\\]\\[0\\]: no link of the robot starts with 'nonexistent_prefix_'"
                      bench unwrap --geometry ${CLASS_TMP}/geo_prefix.json ${GEO_RUN})
topoplan_refused_test(geometry_empty_prefix "geo_empty_prefix\\.json: arm\\.disabled_groups\\[0\\]\\[1\\]: empty prefix"
                      bench unwrap --geometry ${CLASS_TMP}/geo_empty_prefix.json ${GEO_RUN})
# The arm's URDF: an empty path, and errors in loading it name the geometry's arm.urdf (not the
# scenario's robot key).
file(WRITE ${CLASS_TMP}/geo_bad_arm.urdf "<robot name=\"x\"><link name=\"a\"></robot>\n")
file(WRITE ${CLASS_TMP}/geo_bad_arm.json "{\"arm\": {\"urdf\": \"geo_bad_arm.urdf\"}}\n")
file(WRITE ${CLASS_TMP}/geo_empty_arm.json "{\"arm\": {\"urdf\": \"\"}}\n")
topoplan_refused_test(geometry_bad_arm "geo_bad_arm\\.json: arm\\.urdf: .*geo_bad_arm\\.urdf"
                      bench unwrap --geometry ${CLASS_TMP}/geo_bad_arm.json ${GEO_RUN})
topoplan_refused_test(geometry_empty_arm "geo_empty_arm\\.json: arm\\.urdf: empty path"
                      bench unwrap --geometry ${CLASS_TMP}/geo_empty_arm.json ${GEO_RUN})
# A NUL byte ended the JSON text for the parser: what followed it was never read.
add_test(NAME cli.refused_json_nul
         COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "nul\\.json: invalid JSON: a NUL byte at byte offset 13"
                 -- sh -c "rm -rf \"$2\"; printf '{\"name\": \"g\"}\\000garbage' >\"$1\" && \"$0\" bench unwrap --geometry \"$1\" --angles 0:0:15 --planners birrt -o \"$2\"; rc=$?; test ! -e \"$2\" && exit $rc"
                 $<TARGET_FILE:topoplan> ${CLASS_TMP}/nul.json ${CLASS_TMP}/refused_json_nul)
set_tests_properties(cli.refused_json_nul PROPERTIES LABELS unit)
