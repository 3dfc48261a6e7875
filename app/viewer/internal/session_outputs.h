// The outputs a viewer job hands to the draw thread, and how a job records its end: private to
// app/viewer/session*.cc (the session's state machine and its jobs).
#pragma once

#include <deque>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "app/viewer/session.h"
#include "app/viewer/worker.h"

namespace app {

// What a plan (or re-plan) job hands to the draw thread. The job appends under `mutex`; the draw
// thread copies what is new in Poll(). `result` and `scenario` are set once, at the job's end.
struct Session::PlanOutput {
  std::mutex mutex;
  std::vector<SweepRecord> sweeps;
  std::optional<planning::PlanResult> result;
  std::optional<planning::RecedingPlan> horizon;  // re-plan after a move: the new plan
  int frame_at_start = -1;                        // re-plan: the frame shown when it started
  std::vector<RrtTreeView> trees;                 // RRT plans: the trees so far
  long rrt_checks = 0;
  bool finished = false;
  bool stepped = false;  // started by kStep: keep showing the last slice
  bool follow = true;    // show each new sweep (a re-plan keeps playing the old trajectory)
  std::string what = "plan", error;
};

// What the live ODE simulation hands to the draw thread (frames appended under `mutex`).
struct Session::GraspOutput {
  std::mutex mutex;
  GraspReplay replay;
  bool started = false;  // hand and object are set
  bool finished = false;
  bool stepped = false;  // started by kSimStep: keep showing the newest frame at the end
  // What the budgeted units of a stepped run are, in the order asked: {count, whole phases}
  // (a phase unit is StabilityRun::StepPhase, else one physics step); empty: physics steps.
  std::deque<std::pair<long, bool>> units;
  std::string error;
};


// Whether the next budgeted unit of a live simulation is a whole phase (takes it from
// out->units; a run without units steps physics).
template <typename Output>
bool NextUnitIsPhase(Output* out) {
  std::lock_guard<std::mutex> lock(out->mutex);
  if (out->units.empty()) return false;
  const bool phases = out->units.front().second;
  if (--out->units.front().first <= 0) out->units.pop_front();
  return phases;
}

// Runs `job` and records in `out` (under its mutex) that it ended, also when it throws.
template <typename Output, typename Fn>
void RunRecordingEnd(Output* out, Fn&& job) {
  try {
    job();
  } catch (const Worker::Cancelled&) {
    std::lock_guard<std::mutex> lock(out->mutex);
    out->finished = true;
    throw;
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lock(out->mutex);
    out->finished = true;
    out->error = e.what();
    throw;
  }
  std::lock_guard<std::mutex> lock(out->mutex);
  out->finished = true;
}

}  // namespace app
