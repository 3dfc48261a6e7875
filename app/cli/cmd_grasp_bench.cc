// `topoplan bench grasp`: the grasp-transfer study (planning/physics/grasp_study.h) over noisy
// demonstrations, every method on every demonstration, ODE and MuJoCo verdicts, paired
// statistics; grasp.csv is resumable: every finished trial is journalled (fsynced) as it finishes,
// so a run stopped in any way, even SIGKILL or a power loss, continues where it stopped.
#include "app/cli/cmd_grasp_bench.h"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <tuple>

#include "app/cli/io.h"
#include "app/present/grasp_frames.h"
#include "base/assets.h"
#include "base/file_write.h"
#include "base/line_journal.h"
#include "base/str_cat.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/physics/grasp_study.h"
#include "planning/physics/grasp_study_report.h"
#include "planning/physics/ode_runtime.h"

namespace app {
namespace {

namespace fs = std::filesystem;
namespace phys = planning::physics;

struct GraspBenchArgs {
  std::string grasp = "all";
  int demos = 20;
  unsigned seed = 0;
  std::string methods = "winding,winding_only,contact_only,fingertip,joint";
  std::string engines = "all";
  double joint_deg = planning::DemoNoiseOptions{}.joint_deg;
  double palm_mm = planning::DemoNoiseOptions{}.palm_translation * 1e3;
  double palm_deg = planning::DemoNoiseOptions{}.palm_rotation_deg;
  std::string placement = "human_palm";
  int threads = 2;
  int frames = 0;
  bool quick = false;
  double timeout = 0.0;
  std::string output;
};

// The --quick subset: one threading and one control grasp, two demonstrations.
const char* const kQuickGrasps[] = {"ring_grip_torus", "power_bottle"};
constexpr int kQuickDemos = 2;

std::vector<planning::TransferMethod> ParseMethods(const std::string& text) {
  std::vector<planning::TransferMethod> out;
  std::stringstream in(text);
  std::string name;
  while (std::getline(in, name, ',')) {
    const planning::TransferMethod m =
        ParseFlag("--methods", [&] { return planning::ParseTransferMethod(name); });
    if (m == planning::TransferMethod::kHuman) {
      throw std::invalid_argument("--methods: 'human' is the demonstration, not a transfer");
    }
    if (std::find(out.begin(), out.end(), m) != out.end()) {
      throw std::invalid_argument("--methods: '" + name + "' given twice");
    }
    out.push_back(m);
  }
  if (out.empty()) throw std::invalid_argument("--methods: no method given");
  return out;
}

// The protocol a grasp.csv was made with; a rerun resumes only the same protocol.
std::string ProtocolLine(const GraspBenchArgs& a, bool mujoco) {
  char buf[256];
  std::snprintf(buf, sizeof(buf),
                "seed=%u joint_deg=%g palm_mm=%g palm_deg=%g reclose=1 placement=%s mujoco=%d "
                "equal_baselines=1 winding_target=main_reference",
                a.seed, a.joint_deg, a.palm_mm, a.palm_deg, a.placement.c_str(), mujoco ? 1 : 0);
  return buf;
}

// Rows of an earlier run in DIR/grasp.csv (none if absent). The first line is "# protocol: ...",
// then the header. Throws std::invalid_argument if the protocol differs.
std::vector<phys::StudyRow> ReadEarlierRows(const std::string& dir, const std::string& protocol) {
  const fs::path path = fs::path(dir) / "grasp.csv";
  std::vector<phys::StudyRow> rows;
  std::ifstream in(path);
  if (!in) return rows;
  std::string line;
  std::getline(in, line);
  if (line != "# protocol: " + protocol) {
    throw std::invalid_argument("-o: " + path.string() + " was made with another protocol ('" +
                                line + "'); use another folder or remove it");
  }
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (!line.empty()) rows.push_back(phys::ParseStudyCsvRow(line));
  }
  return rows;
}

// The configuration a journal of finished trials belongs to: the protocol (seed, noise, placement,
// engines: every row carries the verdict of each engine of the run) and the row format.
std::string JournalConfiguration(const std::string& protocol) {
  return base::StrCat("bench grasp; ", protocol, "; columns=", phys::StudyCsvHeader());
}

// The identity of a trial: (object, grasp, demonstration, method); the engines are part of the
// configuration.
using TrialKey = std::tuple<std::string, std::string, int, int>;
TrialKey KeyOf(const phys::StudyRow& r) {
  return {r.object, r.grasp, r.demo, static_cast<int>(r.method)};
}

// Adds the trials of the journal that `rows` does not hold yet; returns how many. Throws
// std::invalid_argument "<journal>: record N: ..." for a record that is not a grasp.csv row.
int AddJournalRows(const base::LineJournal& journal, std::vector<phys::StudyRow>* rows) {
  std::set<TrialKey> have;
  for (const phys::StudyRow& r : *rows) have.insert(KeyOf(r));
  int added = 0;
  for (size_t i = 0; i < journal.records().size(); ++i) {
    phys::StudyRow r;
    try {
      r = phys::ParseStudyCsvRow(journal.records()[i]);
    } catch (const std::exception& e) {
      throw std::invalid_argument(base::StrCat(journal.path(), ": record ", std::to_string(i + 1),
                                               ": ", e.what(), "; remove the journal"));
    }
    if (have.insert(KeyOf(r)).second) {
      rows->push_back(r);
      ++added;
    }
  }
  return added;
}

std::string CsvText(const std::string& protocol, std::vector<phys::StudyRow> rows) {
  std::sort(rows.begin(), rows.end(), [](const phys::StudyRow& x, const phys::StudyRow& y) {
    return std::make_tuple(x.grasp, x.demo, static_cast<int>(x.method)) <
           std::make_tuple(y.grasp, y.demo, static_cast<int>(y.method));
  });
  std::string text = "# protocol: " + protocol + "\n" + phys::StudyCsvHeader() + "\n";
  for (const phys::StudyRow& r : rows) text.append(phys::StudyCsvRow(r) + "\n");
  return text;
}

// One unit of work: a demonstration of a grasp and the methods still to run on it.
struct Unit {
  int grasp = 0;
  int demo = 0;
  std::vector<planning::TransferMethod> methods;
};

// Prepared units handed from the worker threads to the thread that runs ODE, in order.
struct Pipeline {
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<std::unique_ptr<phys::StudyUnit>> ready;
  std::vector<std::exception_ptr> errors;
  std::vector<char> done;
  size_t next = 0;      // next unit a worker takes
  size_t consumed = 0;  // units the ODE thread has taken
  bool stop = false;
};

// Up to n trials the engines disagree on, preferring distinct grasps (sorted key order).
std::vector<phys::StudyRow> Disagreements(std::vector<phys::StudyRow> rows, int n) {
  std::sort(rows.begin(), rows.end(), [](const phys::StudyRow& x, const phys::StudyRow& y) {
    return std::make_tuple(x.grasp, x.demo, static_cast<int>(x.method)) <
           std::make_tuple(y.grasp, y.demo, static_cast<int>(y.method));
  });
  std::vector<phys::StudyRow> out;
  for (int pass = 0; pass < 2; ++pass) {
    for (const phys::StudyRow& r : rows) {
      if (static_cast<int>(out.size()) >= n) return out;
      if (!r.mujoco_stable || *r.mujoco_stable == r.ode_stable) continue;
      const bool seen = std::any_of(out.begin(), out.end(),
                                    [&r](const phys::StudyRow& o) { return o.grasp == r.grasp; });
      const bool same = std::any_of(out.begin(), out.end(), [&r](const phys::StudyRow& o) {
        return o.grasp == r.grasp && o.demo == r.demo && o.method == r.method;
      });
      if ((pass == 0 && !seen) || (pass == 1 && !same)) out.push_back(r);
    }
  }
  return out;
}

// Frames of the ODE and the MuJoCo stability test of each row: DIR/frames/<grasp>_<demo>_
// <method>/{ode,mujoco}/stability_*.png (+ contact sheet). The unit is recomputed (deterministic).
void WriteDisagreementFrames(const std::vector<phys::StudyRow>& rows,
                             const planning::GraspInputs& in,
                             const phys::GraspStudyOptions& options, const phys::OdeRuntime& ode,
                             const std::string& dir) {
  if (rows.empty()) return;
  GraspFrameWriter frames;
  for (const phys::StudyRow& r : rows) {
    size_t g = 0;
    while (g < in.grasps.size() && in.grasps[g].name != r.grasp) ++g;
    phys::GraspStudyOptions o = options;
    o.methods = {r.method};
    o.mujoco = false;
    const phys::StudyUnit unit =
        phys::PrepareStudyUnit(in.human, in.lwr_sdh, in.objects, in.grasps[g], r.demo, o);
    std::string name = r.grasp;
    name.append("_" + std::to_string(r.demo) + "_" + planning::ToString(r.method));
    const fs::path base = fs::path(dir) / "frames" / name;
    frames.FinishStability(phys::TestGraspStability(
        ode, unit.hands[0], unit.object, o.stability,
        frames.Stability((base / "ode").string(), unit.hands[0], unit.object, o.stability)));
    frames.FinishStability(phys::TestGraspStabilityMujoco(
        unit.hands[0], unit.object, o.stability, {},
        frames.StabilityStates((base / "mujoco").string(), unit.hands[0], unit.object,
                               o.stability)));
    Note("bench grasp: frames of %s (ODE %s, MuJoCo %s) in frames/%s/{ode,mujoco}", name.c_str(),
         r.ode_stable ? "holds" : "drops", *r.mujoco_stable ? "holds" : "drops", name.c_str());
  }
}

int RunGraspBench(const GraspBenchArgs& a) {
  const std::vector<planning::TransferMethod> methods = ParseMethods(a.methods);
  if (a.engines != "all" && a.engines != "ode" && a.engines != "ode,mujoco") {
    throw std::invalid_argument("--engines: expected all, ode or ode,mujoco");
  }
  const bool mujoco = a.engines != "ode" && phys::EngineAvailable(phys::PhysicsEngine::kMujoco);
  if (a.engines == "ode,mujoco" && !mujoco) {
    throw std::invalid_argument("--engines: this build has no MuJoCo (libmujoco-dev)");
  }
  for (double v : {a.joint_deg, a.palm_mm, a.palm_deg}) {
    if (!(v >= 0 && v <= 90)) {
      throw std::invalid_argument("--joint-noise/--palm-noise: bounds must be in [0, 90]");
    }
  }
  std::vector<std::string> files;
  if (a.quick) {
    for (const char* g : kQuickGrasps) files.push_back(planning::SelectGraspFiles(g).front());
  } else {
    files = planning::SelectGraspFiles(a.grasp);
    if (a.grasp == "all") {  // and the study's own grasps (threading objects), sorted
      const fs::path study = fs::path(base::AssetRoot()) / "grasps" / "study";
      std::vector<std::string> extra;
      if (fs::is_directory(study)) {
        for (const fs::directory_entry& e : fs::directory_iterator(study)) {
          if (e.path().extension() == ".json") extra.push_back(e.path().string());
        }
      }
      std::sort(extra.begin(), extra.end());
      files.insert(files.end(), extra.begin(), extra.end());
    }
  }
  const int demos = a.quick ? kQuickDemos : a.demos;
  OutputDir out(a.output, "-o", "bench grasp", files);
  const std::string protocol = ProtocolLine(a, mujoco);
  std::vector<phys::StudyRow> rows = ReadEarlierRows(a.output, protocol);
  planning::GraspInputs in = planning::LoadGraspInputs(files);
  // The demonstrator re-closes each noisy hand with the joints of the grasp's spec
  // (RecloseDemonstration).
  for (planning::HumanGrasp& g : in.grasps) {
    const fs::path spec = fs::path(base::AssetRoot()) / "grasps" / "specs" / (g.name + ".json");
    if (fs::exists(spec)) g.close = planning::LoadHumanGrasp(spec.string()).close;
  }
  const StopCheck stop(a.timeout);

  phys::GraspStudyOptions options;
  options.noise.seed = a.seed;
  options.noise.joint_deg = a.joint_deg;
  options.noise.palm_translation = a.palm_mm * 1e-3;
  options.noise.palm_rotation_deg = a.palm_deg;
  options.methods = methods;
  options.mujoco = mujoco;
  options.placement = ParseFlag("--placement", [&] {
    return base::ParseEnum<planning::PlacementRule>(a.placement, "placement rule");
  });

  // Units still to run (rows already in grasp.csv are kept and skipped).
  // Trials finished by an earlier run that was killed (SIGKILL, power loss) are in the journal.
  base::LineJournal journal(out.JournalPath("bench-grasp"), JournalConfiguration(protocol));
  const int journalled = AddJournalRows(journal, &rows);
  if (journal.dropped_torn_line()) {
    Note("bench grasp: dropped a torn last line of %s (a write cut short)", journal.path().c_str());
  }
  std::set<TrialKey> have;
  for (const phys::StudyRow& r : rows) have.insert(KeyOf(r));
  std::vector<Unit> todo;
  int total_trials = 0;
  for (size_t g = 0; g < in.grasps.size(); ++g) {
    for (int d = 0; d < demos; ++d) {
      Unit u{static_cast<int>(g), d, {}};
      for (planning::TransferMethod m : methods) {
        const TrialKey key{in.grasps[g].object, in.grasps[g].name, d, static_cast<int>(m)};
        if (!have.count(key)) u.methods.push_back(m);
      }
      total_trials += static_cast<int>(methods.size());
      if (!u.methods.empty()) todo.push_back(u);
    }
  }
  int done_trials = total_trials;
  for (const Unit& u : todo) done_trials -= static_cast<int>(u.methods.size());
  if (done_trials > 0) {
    Note("bench grasp: resuming, %d of %d trials already in %s (grasp.csv, journal: %d)",
         done_trials, total_trials, a.output.c_str(), journalled);
  }

  auto prepare = [&](size_t i) {
    phys::GraspStudyOptions o = options;
    o.methods = todo[i].methods;
    return std::make_unique<phys::StudyUnit>(phys::PrepareStudyUnit(
        in.human, in.lwr_sdh, in.objects, in.grasps[todo[i].grasp], todo[i].demo, o));
  };
  Pipeline p;
  p.ready.resize(todo.size());
  p.errors.resize(todo.size());
  p.done.assign(todo.size(), 0);
  const size_t lookahead = 2 * static_cast<size_t>(a.threads);
  std::vector<std::thread> workers;
  for (int t = 1; t < a.threads; ++t) {
    workers.emplace_back([&] {
      for (;;) {
        size_t i = 0;
        {
          std::unique_lock<std::mutex> lock(p.mutex);
          p.changed.wait(lock, [&] { return p.stop || p.next < p.consumed + lookahead; });
          if (p.stop || p.next >= todo.size()) return;
          i = p.next++;
        }
        std::unique_ptr<phys::StudyUnit> unit;
        std::exception_ptr error;
        try {
          unit = prepare(i);
        } catch (...) {
          error = std::current_exception();
        }
        std::lock_guard<std::mutex> lock(p.mutex);
        p.ready[i] = std::move(unit);
        p.errors[i] = error;
        p.done[i] = 1;
        p.changed.notify_all();
      }
    });
  }
  auto join = [&] {
    {
      std::lock_guard<std::mutex> lock(p.mutex);
      p.stop = true;
    }
    p.changed.notify_all();
    for (std::thread& w : workers) w.join();
    workers.clear();
  };

  phys::OdeRuntime ode;
  const auto start = std::chrono::steady_clock::now();
  int run_trials = 0;
  try {
    for (size_t i = 0; i < todo.size(); ++i) {
      std::unique_ptr<phys::StudyUnit> unit;
      if (workers.empty()) {
        unit = prepare(i);
      } else {
        std::unique_lock<std::mutex> lock(p.mutex);
        while (!p.done[i]) {
          p.changed.wait_for(lock, std::chrono::milliseconds(200));
          lock.unlock();
          stop.Poll();
          lock.lock();
        }
        if (p.errors[i]) std::rethrow_exception(p.errors[i]);
        unit = std::move(p.ready[i]);
        p.consumed = i + 1;
        p.changed.notify_all();
      }
      // Each trial is durable as soon as its verdicts are in. Rows go through their CSV text, so
      // that a resumed run's rows (read back from text) are exactly those of an unbroken run.
      phys::FinishStudyUnit(ode, options, unit.get(), [&](const phys::StudyRow& r) {
        const std::string line = phys::StudyCsvRow(phys::ParseStudyCsvRow(phys::StudyCsvRow(r)));
        journal.Append(line);
        rows.push_back(phys::ParseStudyCsvRow(line));
      });
      run_trials += static_cast<int>(unit->rows.size());
      const double elapsed =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const int now = done_trials + run_trials;
      const double left = elapsed / run_trials * (total_trials - now);
      char bar[21];
      const int filled = 20 * now / std::max(1, total_trials);
      for (int k = 0; k < 20; ++k) bar[k] = k < filled ? '#' : '.';
      bar[20] = '\0';
      Progress("bench grasp [%s] %d/%d trials  %s  %.0f s, ~%.0f s left", bar, now, total_trials,
               unit->demo.name.c_str(), elapsed, left);
      stop.Poll();
    }
  } catch (const StopRequested& e) {
    join();
    EndProgress();
    base::WriteFileAtomic((fs::path(out.staging()) / "grasp.csv").string(),
                          CsvText(protocol, rows));
    out.Commit(false);
    journal.Remove();  // its rows are in grasp.csv now
    std::fprintf(stderr, "%s: kept %zu of %d trials in %s/grasp.csv; rerun to resume\n", e.what(),
                 rows.size(), total_trials, a.output.c_str());
    return e.timeout ? kExitFailed : kExitInterrupted;
  } catch (...) {
    join();
    throw;
  }
  join();
  EndProgress();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const phys::StudySummary summary = phys::SummariseStudy(rows, methods);
  std::string md = "# bench grasp\n\n`" + CommandLine() + "`\n\nProtocol: " + protocol + "; " +
                   std::to_string(in.grasps.size()) + " grasps × " + std::to_string(demos) +
                   " demonstrations × " + std::to_string(methods.size()) + " methods.\n\n";
  md.append(phys::StudyTableMarkdown(summary));
  base::WriteFileAtomic((fs::path(out.staging()) / "grasp.csv").string(), CsvText(protocol, rows));
  base::WriteFileAtomic((fs::path(out.staging()) / "grasp.md").string(), md);
  WriteDisagreementFrames(Disagreements(rows, a.frames), in, options, ode, out.staging());
  out.Commit();
  journal.Remove();
  std::printf("%s", md.c_str());
  Note(
      "bench grasp: %d trials run in %.0f s (%d from an earlier run); wrote %s/grasp.csv, "
      "grasp.md",
      run_trials, seconds, done_trials, a.output.c_str());
  return kExitOk;
}

}  // namespace

void AddGraspBenchCommand(CLI::App* root, CommandList* commands) {
  CLI::App* bench = nullptr;
  for (CLI::App* sub :
       root->get_subcommands([](CLI::App* c) { return c->get_name() == "bench"; })) {
    bench = sub;
  }
  if (!bench) {
    bench = root->add_subcommand("bench", "Benchmarks that reproduce thesis figures");
    bench->require_subcommand(1);
  }
  auto a = std::make_shared<GraspBenchArgs>();
  CLI::App* cmd = bench->add_subcommand(
      "grasp",
      "Grasp-transfer study (issue 36): N noisy demonstrations per grasp type, every SDH method "
      "transfers every demonstration with the same optimiser, starts and shared terms, each "
      "transfer tested in ODE and (if built with it) MuJoCo, compared with its demonstration by "
      "contact-region IoU and thread preservation; McNemar's exact test per method pair.");
  cmd->add_option("--grasp", a->grasp,
                  "grasp name (file stem in assets/grasps), a path, or all (assets/grasps/*.json "
                  "and the study's threading grasps assets/grasps/study/*.json)")
      ->capture_default_str()
      ->check(NonEmpty());
  IntIn(cmd->add_option("--demos", a->demos, "noisy demonstrations per grasp (default 20)"), 1,
        1000);
  cmd->add_option("--seed", a->seed, "seed of the demonstration noise (default 0)");
  cmd->add_option("--methods", a->methods, "comma-separated SDH methods")
      ->capture_default_str()
      ->check(NonEmpty());
  cmd->add_option("--engines", a->engines,
                  "all (ODE, and MuJoCo when this build has it) | ode | ode,mujoco")
      ->capture_default_str()
      ->check(NonEmpty());
  cmd->add_option("--joint-noise", a->joint_deg, "finger joint noise bound [deg]")
      ->capture_default_str()
      ->check(NonEmpty());
  cmd->add_option("--palm-noise-mm", a->palm_mm, "palm translation noise bound per axis [mm]")
      ->capture_default_str()
      ->check(NonEmpty());
  cmd->add_option("--palm-noise-deg", a->palm_deg, "palm rotation noise bound [deg]")
      ->capture_default_str()
      ->check(NonEmpty());
  cmd->add_option("--placement", a->placement,
                  "shared placement stage, the same for every method: human_palm (from the human "
                  "palm pose alone) | object_centre (grasp transfer's rule; reads the object's "
                  "reference and, for loops, the winding target: the ablation)")
      ->capture_default_str()
      ->check(NonEmpty());
  IntIn(cmd->add_option("--threads", a->threads,
                        "threads: N-1 prepare transfers (AICO, MuJoCo) ahead of the one running "
                        "ODE (default 2); the results do not depend on it"),
        1, 64);
  IntIn(cmd->add_option("--frames", a->frames,
                        "also write frames of the ODE and MuJoCo stability tests of N trials the "
                        "engines disagree on (distinct grasps first) into DIR/frames/"),
        0, 100);
  cmd->add_flag("--quick", a->quick,
                "CI subset: ring_grip_torus and power_bottle, 2 demonstrations each");
  AddTimeoutFlag(cmd, &a->timeout);
  cmd->add_option("-o,--output", a->output, "output folder")->required();
  cmd->footer(
      "Writes DIR/grasp.csv (one row per grasp x demonstration x method; first line the "
      "protocol) and DIR/grasp.md (per method stable/trials with Wilson 95 % intervals for all,\n"
      "threading and control objects per engine; McNemar's exact p per method pair; engine\n"
      "agreement). Every finished trial is journalled at once (DIR/.topoplan-journal-bench-grasp,\n"
      "fsynced), so a run stopped in any way (Ctrl-C, --timeout, SIGKILL, power loss) keeps its\n"
      "trials; rerunning the same command skips them (another protocol is refused). Exit 0 when\n"
      "the study ran.");
  commands->push_back({cmd, [a] { return RunGraspBench(*a); }});
}

}  // namespace app
