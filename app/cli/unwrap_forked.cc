#include "app/cli/unwrap_forked.h"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <vector>

#include "app/cli/command.h"
#include "app/cli/forked_jobs.h"
#include "base/byte_codec.h"
#include "base/file_read.h"
#include "base/file_write.h"
#include "base/str_cat.h"

namespace app {
namespace {

namespace fs = std::filesystem;
using planning::PlanReport;
using planning::QueryCounts;
using planning::UnwrapRun;

constexpr std::uint32_t kMagic = 0x32525755;  // "UWR2"

using Writer = base::ByteWriter;
using Reader = base::ByteReader;

// Every field of the report, in declaration order (planner.h PlanReport).
template <typename Io, typename R>
void Fields(Io& io, R& r) {
  io(r.planner);
  io(r.success);
  io(r.status);
  io(r.collision_checks);
  io(r.narrow_phase_calls);
  io(r.iterations);
  io(r.attempts);
  io(r.cost);
  io(r.path_length);
  io(r.time_s);
  io(r.counts);
  io(r.cpu_time_s);
  io(r.setup_time_s);
  io(r.start_writhe_total);
  io(r.final_writhe_total);
  io(r.min_clearance_m);
  io(r.path_collision_free);
  io(r.cost_history);
  io(r.failure_reason);
  io(r.failure_step);
  io(r.reach_error_m);
  io(r.max_winding_jump_turns);
  io(r.winding_jumps);
  io(r.final_winding_turns);
  io(r.writhe_peak_row);
  io(r.writhe_peak_col);
  io(r.writhe_peak_value);
  io(r.failure_detail);
  io(r.loop_checked);
  io(r.passed_through);
  io(r.through_segment);
  io(r.goal_sampler_draws);
  io(r.goal_samples);
  io(r.goal_sampler_counts);
  io(r.goal_sampler_cpu_time_s);
}

struct Put {
  Writer* w;
  void operator()(const std::string& s) { w->String(s); }
  void operator()(const std::vector<double>& v) { w->Doubles(v); }
  template <typename T>
  void operator()(const T& v) {
    w->Pod(v);
  }
};

struct Get {
  Reader* r;
  void operator()(std::string& s) { s = r->String(); }
  void operator()(std::vector<double>& v) { v = r->Doubles(); }
  template <typename T>
  void operator()(T& v) {
    v = r->Pod<T>();
  }
};

std::string EncodeRuns(const std::vector<UnwrapRun>& runs) {
  Writer w;
  w.Pod(kMagic);
  w.Size(runs.size());
  Put put{&w};
  for (const UnwrapRun& run : runs) {
    w.Pod(run.angle_deg);
    w.Pod(run.planner);
    w.Pod(run.seed);
    w.Vec3(run.pole_offset);
    Fields(put, run.report);
    w.String(run.variant);
    w.Pod(run.goal_meets_end_conditions);
    w.Pod(run.unwound_winding_turns);
    w.Pod(run.start_closed_wrap_deg);
    w.Size(run.setup_warnings.size());
    for (const std::string& text : run.setup_warnings) w.String(text);
  }
  w.Pod(kMagic);
  return w.Take();
}

std::vector<UnwrapRun> DecodeRuns(const std::string& bytes) {
  Reader r(bytes, "unwrap runs");
  if (r.Pod<std::uint32_t>() != kMagic) r.Fail();
  std::vector<UnwrapRun> runs(r.Size());
  Get get{&r};
  for (UnwrapRun& run : runs) {
    run.angle_deg = r.Pod<double>();
    run.planner = r.Pod<planning::Planner>();
    run.seed = r.Pod<int>();
    run.pole_offset = r.Vec3();
    Fields(get, run.report);
    run.variant = r.String();
    run.goal_meets_end_conditions = r.Pod<bool>();
    run.unwound_winding_turns = r.Pod<double>();
    run.start_closed_wrap_deg = r.Pod<double>();
    run.setup_warnings.resize(r.Size());
    for (std::string& text : run.setup_warnings) text = r.String();
  }
  if (r.Pod<std::uint32_t>() != kMagic || !r.at_end()) r.Fail();
  return runs;
}

std::string AnglePath(const std::string& dir, size_t a) {
  return (fs::path(dir) / base::StrCat("angle_", std::to_string(a), ".bin")).string();
}

}  // namespace

UnwrapForkedResult RunUnwrapBenchmarkInProcesses(const planning::UnwrapBenchmarkOptions& options,
                                                 const UnwrapRunOptions& run) {
  if (run.workers < 1) throw std::invalid_argument("unwrap runs: workers must be >= 1");
  UnwrapForkedResult out;
  const size_t n = options.angles_deg.size();
  if (run.workers == 1 || n < 2) {
    out.result = planning::RunUnwrapBenchmark(options);
    return out;
  }
  std::vector<size_t> order(n);  // the largest angles first
  for (size_t a = 0; a < n; ++a) order[a] = a;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return options.angles_deg[a] > options.angles_deg[b];
  });
  fs::remove_all(run.scratch_dir);
  fs::create_directories(run.scratch_dir);
  struct Cleanup {
    std::string dir;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(dir, ec);
    }
  } cleanup{run.scratch_dir};
  SharedCounter next;
  const int workers = static_cast<int>(std::min<size_t>(static_cast<size_t>(run.workers), n));
  std::vector<ForkedJob> jobs;
  for (int w = 0; w < workers; ++w) {
    jobs.push_back(
        {base::StrCat("unwrap worker ", std::to_string(w + 1)),
         [&] {
           return RunGuarded("bench unwrap", [&] {
             for (size_t k = next.Next(); k < n; k = next.Next()) {
               planning::UnwrapBenchmarkOptions one = options;
               one.angles_deg = {options.angles_deg[order[k]]};
               const planning::UnwrapBenchmarkResult r = planning::RunUnwrapBenchmark(one);
               base::WriteFileAtomic(AnglePath(run.scratch_dir, order[k]), EncodeRuns(r.runs));
             }
             return 0;
           });
         },
         ""});
  }
  ForkedJobsOptions fo;
  fo.workers = workers;
  fo.should_stop = run.should_stop;
  for (const ForkedJobResult& r : RunForkedJobs(jobs, fo)) {
    out.exit_code = std::max(out.exit_code, r.exit_code);
  }
  planning::UnwrapBenchmarkResult& result = out.result;
  result.angles_deg = options.angles_deg;
  result.planners = options.planners;
  result.seeds = options.seeds;
  for (size_t a = 0; a < n; ++a) {
    const base::FileBytes bytes =
        base::ReadFileLimited(AnglePath(run.scratch_dir, a), std::size_t{1} << 30);
    if (bytes.status != base::ReadStatus::kOk) {
      if (out.exit_code == 0) out.exit_code = kExitEnvironment;  // vanished without a word
      continue;
    }
    for (UnwrapRun& r : DecodeRuns(bytes.bytes)) result.runs.push_back(std::move(r));
  }
  if (out.exit_code == 0) {
    result.summary = planning::SummarizeUnwrapRuns(result.runs, result.angles_deg, result.planners);
  }
  return out;
}

}  // namespace app
