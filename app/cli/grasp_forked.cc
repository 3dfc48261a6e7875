#include "app/cli/grasp_forked.h"

#include <algorithm>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>

#include "app/cli/command.h"
#include "app/cli/forked_jobs.h"
#include "app/present/grasp_frames.h"
#include "base/file_read.h"
#include "base/file_write.h"
#include "base/str_cat.h"
#include "planning/physics/grasp_trial_codec.h"

namespace app {
namespace {

namespace fs = std::filesystem;
namespace phys = planning::physics;

// Removes a folder when it goes out of scope (in the process that made it).
struct ScratchDir {
  explicit ScratchDir(const std::string& path) : path(path) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  std::string path;
};

std::string TrialPath(const std::string& dir, size_t j) {
  return (fs::path(dir) / base::StrCat("trial_", std::to_string(j), ".bin")).string();
}

// The frame writer of one process (run.frames), its stability videos encoded several at a time
// (one ffmpeg start-up for a few videos; flushed before the process's trials are handed back).
std::unique_ptr<GraspFrameWriter> NewFrameWriter(const GraspRunOptions& run) {
  if (!run.frames) return nullptr;
  auto frames = std::make_unique<GraspFrameWriter>();
  frames->set_batch_videos(true);
  return frames;
}

}  // namespace

GraspRunResult RunGraspTrialsInProcesses(const planning::GraspInputs& in,
                                         const std::vector<planning::TransferMethod>& methods,
                                         const phys::GraspTrialsOptions& options,
                                         const GraspRunOptions& run) {
  if (run.workers < 1) throw std::invalid_argument("grasp trials: workers must be >= 1");
  GraspRunResult out;
  if (run.workers == 1) {
    phys::OdeRuntime ode;
    std::unique_ptr<GraspFrameWriter> frames = NewFrameWriter(run);
    phys::GraspTrialsOptions o = options;
    if (run.should_stop) o.should_stop = run.should_stop;
    out.trials =
        phys::RunGraspTrials(ode, in.human, in.lwr_sdh, in.objects, in.grasps, methods, o,
                             GraspTransferHooks(run.out_dir, frames.get(), run.frame_methods));
    if (frames) frames->FlushVideos();
    return out;
  }
  // Every setup (and its errors) here, before any fork; the workers inherit them.
  const phys::GraspTrialsPlan plan(in.human, in.lwr_sdh, in.objects, in.grasps, methods, options);
  const size_t n = plan.num_trials();
  std::vector<size_t> order(n);
  for (size_t j = 0; j < n; ++j) order[j] = j;
  std::stable_partition(order.begin(), order.end(), [&plan](size_t j) {
    return plan.method(j) == planning::TransferMethod::kHuman;
  });
  const ScratchDir scratch(run.scratch_dir);
  SharedCounter next;
  std::vector<ForkedJob> jobs;
  const int workers = static_cast<int>(std::min<size_t>(static_cast<size_t>(run.workers), n));
  for (int w = 0; w < workers; ++w) {
    jobs.push_back({base::StrCat("grasp worker ", std::to_string(w + 1)),
                    [&] {
                      return RunGuarded("grasp trials", [&] {
                        phys::OdeRuntime ode;
                        std::unique_ptr<GraspFrameWriter> frames = NewFrameWriter(run);
                        const phys::GraspTrialHooks hooks =
                            GraspTransferHooks(run.out_dir, frames.get(), run.frame_methods);
                        for (size_t k = next.Next(); k < n; k = next.Next()) {
                          if (run.should_stop && run.should_stop()) break;
                          const phys::GraspTrial trial = plan.RunTrial(ode, order[k], hooks);
                          base::WriteFileAtomic(TrialPath(scratch.path, order[k]),
                                                phys::EncodeGraspTrial(trial));
                        }
                        if (frames) frames->FlushVideos();
                        return 0;
                      });
                    },
                    ""});
  }
  ForkedJobsOptions fo;
  fo.workers = workers;
  fo.should_stop = run.should_stop;
  const std::vector<ForkedJobResult> results = RunForkedJobs(jobs, fo);
  for (const ForkedJobResult& r : results) out.exit_code = std::max(out.exit_code, r.exit_code);
  std::vector<std::optional<phys::GraspTrial>> trials(n);
  for (size_t j = 0; j < n; ++j) {
    const base::FileBytes bytes =
        base::ReadFileLimited(TrialPath(scratch.path, j), std::size_t{1} << 30);
    if (bytes.status == base::ReadStatus::kOk) trials[j] = phys::DecodeGraspTrial(bytes.bytes);
  }
  out.trials = plan.Assemble(std::move(trials));
  if (!out.trials.complete && out.exit_code == 0 && !(run.should_stop && run.should_stop())) {
    out.exit_code = kExitEnvironment;  // a worker vanished without saying why
  }
  return out;
}

}  // namespace app
