#include "planning/physics/grasp_trials.h"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <random>
#include <stdexcept>
#include <thread>

#include "base/line_journal.h"
#include "base/random.h"
#include "planning/grasp/grasp_quality.h"
#include "planning/robot/kinematics.h"

namespace planning::physics {
namespace {

// GraspTrial::epsilon_quality of a finished stability test.
double ClosureEpsilon(const SimObject& object, const StabilityResult& r, double mu) {
  if (r.status == StabilityStatus::kBlownUp && r.message.rfind("closing", 0) == 0) return 0.0;
  std::vector<GraspContact> contacts;
  for (const SimContact& c : r.closure_contacts) {
    if (!c.position.allFinite() || !c.normal.allFinite() || !(c.normal.norm() > 1e-12)) continue;
    contacts.push_back({c.position, -c.normal});
  }
  const ObjectMass mass = ObjectMassProperties(object);
  EpsilonOptions eo;
  eo.radius_of_gyration = std::sqrt(mass.inertia.trace() / (3.0 * mass.mass));
  return EpsilonQuality(contacts, r.closure_world_from_object * mass.com, mu, eo);
}

// Runs the stability test on trial->hand and trial->object, with the hooks around it.
void Simulate(const OdeRuntime& runtime, const TransferSetup& setup,
              const StabilityOptions& options, const GraspTrialHooks& hooks, GraspTrial* trial) {
  StepCallback on_step;
  if (hooks.on_start) {
    on_step = hooks.on_start(setup, trial->transfer, trial->hand, trial->object, options);
  }
  trial->stability = TestGraspStability(runtime, trial->hand, trial->object, options, on_step);
  trial->epsilon_quality = ClosureEpsilon(trial->object, trial->stability, options.sim.mu);
  if (hooks.on_done) hooks.on_done(setup, *trial);
}

// The trial up to its simulation: the transfer (or the demonstration), the hand at its
// configuration (flexion joints driven to their grasp value + close_by) and the object at the
// grasp's pose.
GraspTrial PrepareTrial(const TransferSetup& setup, TransferMethod method, double close_by) {
  GraspTrial trial;
  if (method != TransferMethod::kHuman) {
    trial.transfer = TransferGrasp(setup, method);
    trial.winding_error = (trial.transfer.robot_winding - trial.transfer.target_winding).norm();
    HandBuildOptions build;
    build.close_by = close_by;
    trial.hand = BuildSimHand(setup.sdh, trial.transfer.q, "sdh_palm", build);
  } else {
    trial.human = true;
    TransferResult& t = trial.transfer;
    t.method = TransferMethod::kHuman;
    t.q = setup.human_q;
    KinematicsData kin(setup.human);
    ForwardKinematics(setup.human, setup.human_q, &kin);
    const GraspEncoding enc = EncodeGrasp(setup.human, kin, setup.human_chains, setup.reference);
    t.human_winding = t.target_winding = t.robot_winding = enc.finger;
    t.human_phalanx_winding = t.robot_phalanx_winding = enc.phalanx;
    // The demonstration's own opposition pairs about the extra curves: target = achieved.
    if (!setup.extra_references.empty()) {
      t.target_extra_winding = t.robot_extra_winding =
          WindingTarget(setup).tail(2 * setup.extra_references.size());
    }
    t.min_clearance = HandClearance(setup.human, kin, SampleHandSpheres(setup.human, {}, 0.002),
                                    setup.object, setup.grasp.world_from_object);
    t.solver = "demonstration";
    t.iterations = 0;
    HandBuildOptions build = HumanHandBuildOptions();
    build.close_by = close_by;
    trial.hand = BuildSimHand(setup.human, setup.human_q, "hand_palm", build);
  }
  trial.object = BuildSimObject(setup.object, setup.grasp.world_from_object);
  return trial;
}

// The perturbed repetitions of a prepared and simulated trial (no hooks).
void RunPerturbed(const OdeRuntime& runtime, const TransferSetup& setup,
                  const StabilityOptions& stability, const GraspTrialsOptions& options,
                  GraspTrial* trial) {
  for (int k = 0; k < options.perturb; ++k) {
    PerturbedTrial p;
    p.world_from_object =
        PerturbedObjectPose(setup.grasp.world_from_object, setup.grasp.name, k, options);
    const SimObject object = BuildSimObject(setup.object, p.world_from_object);
    const StabilityResult r = TestGraspStability(runtime, trial->hand, object, stability);
    p.stable = r.stable;
    p.directions_passed = r.directions_passed;
    p.epsilon_quality = ClosureEpsilon(object, r, stability.sim.mu);
    trial->perturbed_stable += p.stable ? 1 : 0;
    trial->perturbed.push_back(p);
  }
}

// FNV-1a 64 of a name.
std::uint64_t NameHash(const std::string& name) { return base::Fnv1a64(name); }

void CheckTrialsOptions(const GraspTrialsOptions& o) {
  if (!(o.mu >= 0) || !std::isfinite(o.mu)) {
    throw std::invalid_argument("grasp trials: mu must be a finite number >= 0");
  }
  if (!(o.contact_patch_radius >= 0) || !std::isfinite(o.contact_patch_radius)) {
    throw std::invalid_argument("grasp trials: contact_patch_radius must be a finite number >= 0");
  }
  if (!(o.close_by >= 0 && o.close_by <= GraspTrialsOptions::kMaxCloseBy)) {
    throw std::invalid_argument("grasp trials: close_by must be in [0, 0.5] rad");
  }
  if (o.perturb < 0 || o.perturb > 1000) {
    throw std::invalid_argument("grasp trials: perturb must be in [0, 1000]");
  }
  if (o.threads < 1) throw std::invalid_argument("grasp trials: threads must be >= 1");
  if (!(o.perturb_translation >= 0) || !std::isfinite(o.perturb_translation) ||
      !(o.perturb_rotation_deg >= 0) || !std::isfinite(o.perturb_rotation_deg)) {
    throw std::invalid_argument("grasp trials: perturbation sizes must be finite and >= 0");
  }
}

// Transfers computed ahead by worker threads, claimed in job order (grasp-major); the calling
// thread claims a job itself when no worker has started it yet.
class TransferQueue {
 public:
  TransferQueue(const std::vector<TransferSetup>& setups,
                const std::vector<TransferMethod>& methods, double close_by, int workers)
      : setups_(setups),
        methods_(methods),
        close_by_(close_by),
        slots_(setups.size() * methods.size()) {
    for (int w = 0; w < workers; ++w) threads_.emplace_back([this] { Work(); });
  }
  ~TransferQueue() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    for (std::thread& t : threads_) t.join();
  }
  TransferQueue(const TransferQueue&) = delete;
  TransferQueue& operator=(const TransferQueue&) = delete;

  // The prepared trial of job j (computed here if nobody claimed it); rethrows its exception.
  GraspTrial Take(size_t j) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (next_ <= j) {  // jobs are claimed in order: j is not started, nor any after it
      next_ = j + 1;
      lock.unlock();
      Compute(j);
      lock.lock();
    }
    done_.wait(lock, [&] { return slots_[j].ready; });
    Slot slot = std::move(slots_[j]);
    if (slot.error) std::rethrow_exception(slot.error);
    return std::move(slot.trial);
  }

 private:
  struct Slot {
    bool ready = false;
    GraspTrial trial;
    std::exception_ptr error;
  };

  void Compute(size_t j) {
    Slot slot;
    try {
      slot.trial =
          PrepareTrial(setups_[j / methods_.size()], methods_[j % methods_.size()], close_by_);
    } catch (...) {
      slot.error = std::current_exception();
    }
    slot.ready = true;
    std::lock_guard<std::mutex> lock(mutex_);
    slots_[j] = std::move(slot);
    done_.notify_all();
  }

  void Work() {
    while (true) {
      size_t j;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_ || next_ >= slots_.size()) return;
        j = next_++;
      }
      Compute(j);
    }
  }

  const std::vector<TransferSetup>& setups_;
  const std::vector<TransferMethod>& methods_;
  const double close_by_;
  std::vector<Slot> slots_;
  std::mutex mutex_;
  std::condition_variable done_;
  size_t next_ = 0;
  bool stop_ = false;
  std::vector<std::thread> threads_;
};

// The result's protocol fields (no trials yet).
GraspTrialsResult ResultHeader(const std::vector<TransferMethod>& methods,
                               const GraspTrialsOptions& options) {
  GraspTrialsResult result;
  result.methods = methods;
  result.stability.sim.mu = options.mu;
  result.stability.sim.contact_patch_radius = options.contact_patch_radius;
  result.close_by = options.close_by;
  result.perturb = options.perturb;
  result.seed = options.seed;
  result.perturb_translation = options.perturb_translation;
  result.perturb_rotation_deg = options.perturb_rotation_deg;
  return result;
}

std::vector<TransferSetup> MakeSetups(const Robot& human_hand, const Robot& sdh_source,
                                      const std::vector<GraspObject>& objects,
                                      const std::vector<HumanGrasp>& grasps) {
  std::vector<TransferSetup> setups;
  for (const HumanGrasp& g : grasps) {
    setups.push_back(
        MakeTransferSetup(human_hand, sdh_source, FindGraspObject(objects, g.object), g));
  }
  return setups;
}

// Per-method summaries and all_stable of the trials in `result`.
void Summarise(GraspTrialsResult* result) {
  const std::vector<TransferMethod>& methods = result->methods;
  for (size_t mi = 0; mi < methods.size(); ++mi) {
    GraspMethodSummary s;
    s.method = methods[mi];
    s.grasps = static_cast<int>(result->trials.size());
    for (const std::vector<GraspTrial>& row : result->trials) {
      const GraspTrial& t = row[mi];
      s.stable += t.stability.stable ? 1 : 0;
      result->all_stable = result->all_stable && t.stability.stable;
      s.perturbed_trials += static_cast<int>(t.perturbed.size());
      s.perturbed_stable += t.perturbed_stable;
    }
    s.rate = static_cast<double>(s.stable) / std::max(1, s.grasps);
    if (s.grasps > 0) s.ci95 = WilsonInterval(s.stable, s.grasps);
    s.perturbed_rate = static_cast<double>(s.perturbed_stable) / std::max(1, s.perturbed_trials);
    if (s.perturbed_trials > 0) {
      s.perturbed_ci95 = WilsonInterval(s.perturbed_stable, s.perturbed_trials);
    }
    result->summary.push_back(s);
  }
}

}  // namespace

Eigen::Isometry3d PerturbedObjectPose(const Eigen::Isometry3d& world_from_object,
                                      const std::string& grasp_name, int k,
                                      const GraspTrialsOptions& options) {
  const std::uint64_t h = NameHash(grasp_name);
  std::seed_seq seq{options.seed, static_cast<std::uint32_t>(h),
                    static_cast<std::uint32_t>(h >> 32), static_cast<std::uint32_t>(k)};
  std::mt19937 rng(seq);
  auto symmetric = [&rng](double a) { return a * (2.0 * base::UniformUnit(&rng) - 1.0); };
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) t[i] = symmetric(options.perturb_translation);
  const Eigen::Vector3d axis = base::UniformUnitVector(&rng);
  const double angle = symmetric(options.perturb_rotation_deg * M_PI / 180.0);
  Eigen::Isometry3d pose = world_from_object;
  pose.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * world_from_object.linear();
  pose.translation() += t;
  return pose;
}

GraspTrial RunGraspTrial(const OdeRuntime& runtime, const TransferSetup& setup,
                         TransferMethod method, const StabilityOptions& options,
                         const GraspTrialHooks& hooks) {
  GraspTrial trial = PrepareTrial(setup, method, HandBuildOptions{}.close_by);
  Simulate(runtime, setup, options, hooks, &trial);
  return trial;
}

GraspTrial RunHumanTrial(const OdeRuntime& runtime, const TransferSetup& setup,
                         const StabilityOptions& options, const GraspTrialHooks& hooks) {
  return RunGraspTrial(runtime, setup, TransferMethod::kHuman, options, hooks);
}

GraspTrialsResult RunGraspTrials(const OdeRuntime& runtime, const Robot& human_hand,
                                 const Robot& sdh_source, const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods,
                                 const GraspTrialsOptions& options, const GraspTrialHooks& hooks) {
  CheckTrialsOptions(options);
  GraspTrialsResult result = ResultHeader(methods, options);
  // Every setup first, so that a bad grasp or object fails before any work.
  const std::vector<TransferSetup> setups = MakeSetups(human_hand, sdh_source, objects, grasps);
  {
    TransferQueue queue(setups, methods, options.close_by,
                        methods.empty() ? 0 : options.threads - 1);
    for (size_t gi = 0; gi < grasps.size() && result.complete; ++gi) {
      std::vector<GraspTrial> row;
      for (size_t mi = 0; mi < methods.size(); ++mi) {
        if (options.should_stop && options.should_stop()) {
          result.complete = false;
          break;
        }
        GraspTrial trial = queue.Take(gi * methods.size() + mi);
        Simulate(runtime, setups[gi], result.stability, hooks, &trial);
        RunPerturbed(runtime, setups[gi], result.stability, options, &trial);
        row.push_back(std::move(trial));
      }
      if (!result.complete) break;
      result.grasps.push_back(grasps[gi]);
      result.trials.push_back(std::move(row));
    }
  }
  Summarise(&result);
  return result;
}

GraspTrialsPlan::GraspTrialsPlan(const Robot& human_hand, const Robot& sdh_source,
                                 const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods,
                                 const GraspTrialsOptions& options)
    : grasps_(grasps), methods_(methods), options_(options) {
  CheckTrialsOptions(options);
  stability_ = ResultHeader(methods, options).stability;
  setups_ = MakeSetups(human_hand, sdh_source, objects, grasps);
}

GraspTrial GraspTrialsPlan::RunTrial(const OdeRuntime& runtime, size_t j,
                                     const GraspTrialHooks& hooks) const {
  if (j >= num_trials()) throw std::out_of_range("grasp trials: no such trial");
  GraspTrial trial = PrepareTrial(setup(j), method(j), options_.close_by);
  Simulate(runtime, setup(j), stability_, hooks, &trial);
  RunPerturbed(runtime, setup(j), stability_, options_, &trial);
  return trial;
}

GraspTrialsResult GraspTrialsPlan::Assemble(std::vector<std::optional<GraspTrial>> trials) const {
  if (trials.size() != num_trials()) {
    throw std::invalid_argument("grasp trials: one entry per trial expected");
  }
  GraspTrialsResult result = ResultHeader(methods_, options_);
  for (size_t gi = 0; gi < grasps_.size() && result.complete; ++gi) {
    std::vector<GraspTrial> row;
    for (size_t mi = 0; mi < methods_.size(); ++mi) {
      std::optional<GraspTrial>& t = trials[gi * methods_.size() + mi];
      if (!t) {
        result.complete = false;
        break;
      }
      row.push_back(std::move(*t));
    }
    if (!result.complete) break;
    result.grasps.push_back(grasps_[gi]);
    result.trials.push_back(std::move(row));
  }
  Summarise(&result);
  return result;
}

GraspTrialsResult RunGraspTrials(const OdeRuntime& runtime, const Robot& human_hand,
                                 const Robot& sdh_source, const std::vector<GraspObject>& objects,
                                 const std::vector<HumanGrasp>& grasps,
                                 const std::vector<TransferMethod>& methods, double mu,
                                 const GraspTrialHooks& hooks) {
  GraspTrialsOptions options;
  options.mu = mu;
  return RunGraspTrials(runtime, human_hand, sdh_source, objects, grasps, methods, options, hooks);
}

}  // namespace planning::physics
