# Inputs of the robustness check that were still accepted wrongly (included by
# tests/cli/CMakeLists.txt).
# Optional output flags given as "" are refused (exit 2) instead of being ignored: `diff -o ""`,
# `writhe --heatmap ""` and `grasp synthesize -o ""`; `grasp synthesize -o` is checked before the
# synthesis. CTest drops empty arguments: these go through sh.
set(GALLERY ${PROJECT_SOURCE_DIR}/docs/gallery/hopf_heatmap.png)
set(SPEC ${PROJECT_SOURCE_DIR}/assets/grasps/specs/power_bottle.json)
foreach(case "diff|-o|diff ${GALLERY} ${GALLERY} -o"
             "writhe|--heatmap|writhe ${CHAINS}/hopf_a.csv ${CHAINS}/hopf_b.csv --heatmap"
             "synthesize|-o|grasp synthesize ${SPEC} -o")
  string(REPLACE "|" ";" parts "${case}")
  list(GET parts 0 name)
  list(GET parts 1 flag)
  list(GET parts 2 cmd)
  add_test(NAME cli.limit_empty_output_${name}
           COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/expect.sh 2 "${flag}: empty output path" --
                   sh -c "\"$0\" ${cmd} \"\"" $<TARGET_FILE:topoplan>)
  set_tests_properties(cli.limit_empty_output_${name} PROPERTIES LABELS unit)
endforeach()
topoplan_cli_test(limit_synthesize_unusable_output 2 "-o: '/dev/null': /dev/null is not a folder"
                  grasp synthesize ${SPEC} -o /dev/null/g.json)
