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
