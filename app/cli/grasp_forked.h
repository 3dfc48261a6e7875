// The grasp-transfer trials (planning::physics::RunGraspTrials) spread over forked worker
// processes: the demo's grasp stage on several cores. ODE is not thread-safe in Debian's build and
// every frame writer needs a GL context of its own, so the trials run in processes, each claiming
// the next trial from a counter they share; each trial comes back as bytes in a scratch file.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "planning/grasp/grasp_inputs.h"
#include "planning/physics/grasp_trials.h"

namespace app {

struct GraspRunOptions {
  // Processes running trials at the same time: 1 runs RunGraspTrials in this process (threads
  // from the trials' options); > 1 forks that many workers (one thread each). Only call with
  // workers > 1 from a single-threaded process.
  int workers = 1;
  // Frames of the trials under OUT_DIR/frames/ (GraspTransferHooks(out_dir, frames,
  // frame_methods)); the progress lines of the trials go to stderr either way.
  bool frames = false;
  // With `frames`: only the trials of these methods are drawn (empty: every trial).
  std::vector<planning::TransferMethod> frame_methods;
  std::string out_dir;
  // workers > 1: the trials pass through this folder (created; removed before returning).
  std::string scratch_dir;
  // Polled between trials (and by the parent every 50 ms); once true, no further trial starts.
  std::function<bool()> should_stop;
};

struct GraspRunResult {
  planning::physics::GraspTrialsResult trials;  // complete = false when stopped early
  int exit_code = 0;  // the worst exit code of a worker (2 bad input, 3 environment, ...)
};

// RunGraspTrials(in.human, in.lwr_sdh, in.objects, in.grasps, methods, options) with the frame
// hooks: the same result, frames and files whatever `run.workers` (the trials are independent
// and deterministic). Trials of the human hand are claimed first (the longest simulations).
GraspRunResult RunGraspTrialsInProcesses(const planning::GraspInputs& in,
                                         const std::vector<planning::TransferMethod>& methods,
                                         const planning::physics::GraspTrialsOptions& options,
                                         const GraspRunOptions& run);

}  // namespace app
