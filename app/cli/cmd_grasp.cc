// `topoplan grasp synthesize` and `topoplan grasp transfer`: human grasps, their winding encoding,
// transfer to the Schunk SDH and the ODE stability test.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "app/cli/command.h"
#include "app/cli/figure_flags.h"
#include "app/cli/io.h"
#include "app/present/grasp_frames.h"
#include "app/present/reports.h"
#include "base/assets.h"
#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/grasp/grasp_object.h"
#include "planning/grasp/grasp_transfer.h"
#include "planning/physics/grasp_trials.h"
#include "planning/physics/ode_runtime.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/robot_io.h"
#include "visualize/figures.h"

namespace app {
namespace {

struct SynthesizeArgs {
  std::string spec_path, out_path;
  bool out_given = false;  // -o given (possibly as "")
};

int RunSynthesize(const SynthesizeArgs& a) {
  if (a.out_given)
    base::CheckOutputFile(a.out_path, "-o", {a.spec_path});  // before any work; "" is refused
  const std::vector<planning::GraspObject> objects =
      planning::LoadGraspObjects(base::AssetPath("grasps/objects.json"));
  planning::Robot human = planning::LoadRobot(base::AssetPath("robots/human_hand.urdf"));
  planning::HumanGrasp grasp = planning::LoadHumanGrasp(a.spec_path);
  const planning::GraspObject& object = planning::FindGraspObject(objects, grasp.object);
  const double clearance = planning::SynthesizeGrasp(human, object, &grasp);
  // Report contacts and the winding encoding so the result can be judged before it is stored.
  const std::vector<int> chains = planning::AddGraspChains(true, &human);
  planning::KinematicsData kin(human);
  planning::ForwardKinematics(human, planning::HumanConfiguration(human, grasp), &kin);
  const planning::HandSpheres spheres = planning::SampleHandSpheres(human, {}, 0.002);
  std::vector<double> per_link;
  planning::HandClearance(human, kin, spheres, object, grasp.world_from_object, &per_link);
  std::printf("%s: min clearance %.2f mm\n", grasp.name.c_str(), clearance * 1e3);
  for (size_t i = 0; i < per_link.size(); ++i) {
    if (per_link[i] < 0.002) {
      std::printf("  contact %-18s %+.2f mm\n", human.links[i].name.c_str(), per_link[i] * 1e3);
    }
  }
  const planning::GraspEncoding enc = planning::EncodeGrasp(
      human, kin, chains, planning::TransformReference(object.reference, grasp.world_from_object));
  for (int f = 0; f < enc.finger.size(); ++f) {
    Eigen::Matrix3Xd points;
    planning::ChainPoints(human, kin, chains[f], &points);
    const Eigen::Vector3d tip = points.col(points.cols() - 1);
    std::printf("  winding %-7s %+.3f  tip (%+.3f, %+.3f, %+.3f)\n",
                planning::HumanFingers()[f].c_str(), enc.finger[f], tip.x(), tip.y(), tip.z());
  }
  for (const auto& [name, v] : grasp.joints) std::printf("  %-16s %+.4f\n", name.c_str(), v);
  grasp.close.clear();
  if (!a.out_path.empty()) base::WriteFileAtomic(a.out_path, planning::HumanGraspToJson(grasp));
  return kExitOk;
}

struct TransferArgs {
  std::string grasp = "all";
  std::string method = "all";
  double mu = 1.0;
  double contact_patch_mm = planning::physics::SimOptions{}.contact_patch_radius * 1e3;
  double close_by = planning::physics::HandBuildOptions{}.close_by;
  std::string out_dir;
  double timeout = 0.0;
  bool frames = false;
  bool json = false;
  int perturb = 0;
  unsigned seed = 0;
  int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::vector<render::FigureFormat> formats;  // --formats
};

int RunTransfer(const TransferArgs& a) {
  if (!(a.mu >= 0) || !std::isfinite(a.mu)) {
    throw std::invalid_argument("--mu: must be a finite number >= 0");
  }
  if (!(a.contact_patch_mm >= 0 && a.contact_patch_mm <= 50)) {
    throw std::invalid_argument("--contact-patch: must be a number of mm in [0, 50]");
  }
  if (!(a.close_by >= 0 && a.close_by <= planning::physics::GraspTrialsOptions::kMaxCloseBy)) {
    throw std::invalid_argument("--close-by: must be a number of radians in [0, 0.5]");
  }
  std::vector<planning::TransferMethod> methods;
  if (a.method == "all") {
    methods = planning::AllTransferMethods();
  } else {
    methods = {ParseFlag("--method", [&] { return planning::ParseTransferMethod(a.method); })};
  }
  const std::vector<std::string> grasp_files = planning::SelectGraspFiles(a.grasp);
  OutputDir out(a.out_dir, "-o", "grasp transfer", grasp_files);  // checked before any work
  const StopCheck stop(a.timeout);
  // Load everything first so that a bad file fails before any simulation runs.
  const planning::GraspInputs in = planning::LoadGraspInputs(grasp_files);

  namespace phys = planning::physics;
  phys::OdeRuntime ode;
  std::unique_ptr<GraspFrameWriter> frames;
  if (a.frames) frames = std::make_unique<GraspFrameWriter>();
  const phys::GraspTrialHooks hooks = GraspTransferHooks(out.staging(), frames.get());
  phys::GraspTrialsOptions options;
  options.mu = a.mu;
  options.contact_patch_radius = a.contact_patch_mm * 1e-3;
  options.close_by = a.close_by;
  options.perturb = a.perturb;
  options.seed = a.seed;
  options.threads = a.threads;
  // Stops between trials; a stopped run keeps the grasps whose trials all finished.
  std::optional<StopRequested> stopped;
  options.should_stop = [&stop, &stopped] {
    try {
      stop.Poll();
      return false;
    } catch (const StopRequested& e) {
      stopped = e;
      return true;
    }
  };
  const phys::GraspTrialsResult result = phys::RunGraspTrials(ode, in.human, in.lwr_sdh, in.objects,
                                                              in.grasps, methods, options, hooks);
  if (stopped) {
    WriteGraspOutputs(result, out.staging(),
                      StoppedReportJson(*stopped, planning::physics::GraspReportJson(result)),
                      a.formats);
    out.Commit();
    std::fprintf(stderr, "%s: wrote %s/report.json (%zu of %zu grasps)\n", stopped->what(),
                 a.out_dir.c_str(), result.grasps.size(), in.grasps.size());
    return stopped->timeout ? kExitFailed : kExitInterrupted;
  }

  const std::string text = WriteGraspOutputs(result, out.staging(), a.formats);
  out.Commit();
  if (a.json) std::cout << text;
  std::fprintf(stderr, "wrote %s/report.json, summary.md, summary.png\n", a.out_dir.c_str());
  return result.all_stable ? kExitOk : kExitFailed;
}

}  // namespace

void AddGraspCommands(CLI::App* root, CommandList* commands) {
  CLI::App* grasp = root->add_subcommand("grasp", "Human grasps, winding encoding, SDH transfer");
  grasp->require_subcommand(1);

  auto sa = std::make_shared<SynthesizeArgs>();
  CLI::App* synth = grasp->add_subcommand(
      "synthesize",
      "Close the joints listed in a grasp spec's \"close\" array until they touch the object, "
      "print contacts and windings, and write the resulting grasp file");
  synth->add_option("spec", sa->spec_path, "grasp file with a \"close\" list")->required();
  synth->add_option("-o,--output", sa->out_path, "output grasp file (JSON)");
  commands->push_back({synth, [sa, synth] {
                         sa->out_given = synth->count("-o") > 0;
                         return RunSynthesize(*sa);
                       }});

  auto ta = std::make_shared<TransferArgs>();
  CLI::App* transfer = grasp->add_subcommand(
      "transfer",
      "Transfer human grasps (assets/grasps/*.json) to the Schunk SDH by winding numbers (AICO) "
      "and by the ablations and baselines (all methods differ only in their target term), and "
      "test each transferred grasp and the human demonstration itself in ODE: close with "
      "gravity off, then gravity along the 6 palm axes for 2 s each. "
      "Writes DIR/report.json, DIR/summary.md, DIR/summary.png. Exit 0 if every tested grasp is "
      "stable, 1 if some is not, 2 for bad input.");
  transfer
      ->add_option("--grasp", ta->grasp, "grasp name (file stem in assets/grasps), a path, or all")
      ->capture_default_str()
      ->check(NonEmpty());
  transfer
      ->add_option("--method", ta->method,
                   "winding | winding_only | contact_only | fingertip | joint | human | all")
      ->capture_default_str()
      ->check(NonEmpty());
  transfer->add_option("--mu", ta->mu, "Coulomb friction coefficient (friction pyramid)")
      ->capture_default_str()
      ->check(NonEmpty());
  transfer
      ->add_option("--contact-patch", ta->contact_patch_mm,
                   "soft-finger contact patch radius in mm, the same for every method and the "
                   "human hand: torsional friction up to (3 pi/16) mu a times the normal force; "
                   "0 = point contacts")
      ->capture_default_str()
      ->check(NonEmpty());
  transfer
      ->add_option("--close-by", ta->close_by,
                   "grip: the fingers' flexion joints are driven to their grasp value + RAD, the "
                   "same for every method and the human hand (in [0, 0.5])")
      ->capture_default_str()
      ->check(NonEmpty());
  transfer->add_option("-o,--output", ta->out_dir, "output folder")->required();
  AddTimeoutFlag(transfer, &ta->timeout);
  transfer->add_flag("--frames", ta->frames,
                     "also write frames of the transfer and stability test");
  transfer->add_flag("--json", ta->json, "print report.json to stdout");
  IntIn(transfer->add_option(
            "--repeats", ta->perturb,
            "also repeat every grasp and method N times with the object moved by up to "
            "+-5 mm per axis and turned by up to +-5 deg (seeded); report.json then gives "
            "per grasp and method perturbed: {trials, stable, ci95} (Wilson 95 %)"),
        1, 1000);
  IntIn(AddDeprecatedAlias(transfer, "--perturb", "--repeats", &ta->perturb), 1, 1000);
  transfer->add_option("--seed", ta->seed, "seed of the perturbations (default 0)");
  IntIn(transfer->add_option("--threads", ta->threads,
                             "threads computing transfers ahead of the simulations (default: the "
                             "number of cores); the results do not depend on it"),
        1, 256);
  AddFormatsFlag(transfer, &ta->formats);
  commands->push_back({transfer, [ta] { return RunTransfer(*ta); }});
}

}  // namespace app
