# Good runs of the commands that plan and draw (included by tests/app/cli/CMakeLists.txt). Together
# with the bad-input tests (cli.*, robot_cli.*, grasp_cli.*) scripts/run.sh also runs them against
# the ASan + UBSan build (SANITIZE=1), so they are small: `plan --frames` of the tinyarm scenario
# (AICO, per-frame writhe heatmaps, frames through OSMesa) and the headless viewer driven by a
# script (AICO sweeps stepped, a plan on the worker thread while frames are drawn, a screenshot
# mid-run).
set(RUN_TMP ${CMAKE_CURRENT_BINARY_DIR}/runs)
file(MAKE_DIRECTORY ${RUN_TMP})
topoplan_cli_test(run_plan_frames 0 "wrote .*report\\.json"
                  plan tinyarm_ring --frames -o ${RUN_TMP}/plan_frames)
file(WRITE ${RUN_TMP}/viewer_script.txt
     "step 2\nplan async\nframes 2\nwait\nseek 1\nscreenshot ${RUN_TMP}/viewer_mid.png\n"
     "toggle heatmap\nframes 2\n")
topoplan_cli_test(run_view_script 0 "wrote .*viewer\\.png \\(320x240"
                  view reach_through_ring --size 320x240 --script ${RUN_TMP}/viewer_script.txt
                  --screenshot ${RUN_TMP}/viewer.png)
set_tests_properties(cli.run_plan_frames cli.run_view_script PROPERTIES
                     LABELS snapshot ENVIRONMENT GALLIUM_DRIVER=llvmpipe TIMEOUT 600)
