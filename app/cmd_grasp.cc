// `topoplan grasp synthesize` and `topoplan grasp transfer`: human grasps, their winding encoding,
// transfer to the Schunk SDH and the ODE stability test.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/assets.h"
#include "app/command.h"
#include "app/grasp_scene.h"
#include "app/io.h"
#include "app/scene_builder.h"
#include "planning/grasp.h"
#include "planning/grasp_object.h"
#include "planning/grasp_transfer.h"
#include "planning/kinematics.h"
#include "planning/physics/hand_builder.h"
#include "planning/physics/ode_runtime.h"
#include "planning/physics/stability.h"
#include "planning/robot_io.h"
#include "render/frames.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/plot.h"
#include "render/renderer.h"
#include "render/scene.h"

namespace app {
namespace {

struct SynthesizeArgs {
  std::string spec_path, out_path;
};

int RunSynthesize(const SynthesizeArgs& a) {
  const std::vector<planning::GraspObject> objects =
      planning::LoadGraspObjects(AssetPath("grasps/objects.json"));
  planning::Robot human = planning::LoadRobot(AssetPath("robots/human_hand.urdf"));
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
  if (!a.out_path.empty()) WriteFileAtomic(a.out_path, planning::HumanGraspToJson(grasp));
  return kExitOk;
}

struct TransferArgs {
  std::string grasp = "all";
  std::string method = "all";
  double mu = 1.0;
  std::string out_dir;
  bool frames = false;
  bool json = false;
};

// Grasp files selected by --grasp: "all" = every *.json directly in assets/grasps/ except
// objects.json (sorted by name), a name (assets/grasps/NAME.json) or a path to a file.
std::vector<std::string> SelectGraspFiles(const std::string& which) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  if (which == "all") {
    for (const auto& e : fs::directory_iterator(AssetPath("grasps"))) {
      const fs::path& p = e.path();
      if (e.is_regular_file() && p.extension() == ".json" && p.filename() != "objects.json") {
        files.push_back(p.string());
      }
    }
    std::sort(files.begin(), files.end());
  } else if (fs::exists(which)) {
    files.push_back(which);
  } else if (which.find('/') != std::string::npos || fs::path(which).extension() == ".json") {
    throw std::invalid_argument("--grasp: " + which + ": cannot open grasp file");
  } else {
    const fs::path p = fs::path(AssetRoot()) / "grasps" / (which + ".json");
    if (!fs::exists(p)) {
      throw std::invalid_argument("--grasp: no grasp file '" + which + "' (looked for " +
                                  p.string() + ")");
    }
    files.push_back(p.string());
  }
  return files;
}

nlohmann::json VecJson(const Eigen::VectorXd& v) {
  nlohmann::json a = nlohmann::json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) a.push_back(std::round(v[i] * 1e6) / 1e6);
  return a;
}

double Round(double v, double scale = 1e6) { return std::round(v * scale) / scale; }

// --- Frames ------------------------------------------------------------------------------------

constexpr int kFrameWidth = 480;
constexpr int kFrameHeight = 360;

// Renders the human grasp, the SDH approach (AICO slices) and the final SDH grasp, then the ODE
// closing and the six gravity trials, into DIR/frames/<grasp>_<method>/.
class GraspFrameWriter {
 public:
  GraspFrameWriter() : renderer_(context_.proc_loader()) {}

  void Transfer(const std::string& dir, const planning::TransferSetup& setup,
                const planning::TransferResult& t) {
    render::FrameWriterOptions fo;
    fo.prefix = "transfer_";
    fo.video = false;
    render::FrameWriter writer(dir, fo);
    SceneBuildOptions opt;
    opt.grid = false;
    opt.chains = true;
    // Human grasp.
    planning::KinematicsData hk(setup.human);
    planning::ForwardKinematics(setup.human, setup.human_q, &hk);
    render::Scene human;
    AddRobotShapes(setup.human, hk, Eigen::Isometry3d::Identity(), opt, &cache_, &human);
    AddGraspObjectShapes(setup.object, setup.grasp.world_from_object, &human);
    // Look at the palm from the object's side: along the SDH placement's z (palm normal), offset
    // sideways so fingers and object separate.
    const Eigen::Matrix3d rs = setup.sdh_placement.linear();
    view_ = (rs * Eigen::Vector3d(0.5, 0.6, 1.0)).cast<float>();
    camera_ = FrameSceneCamera(human, view_, 40.0f);
    writer.Add(renderer_.Render(human, camera_, kFrameWidth, kFrameHeight));
    planning::KinematicsData sk(setup.sdh);
    for (int c = 0; c < t.trajectory.q.cols(); ++c) {
      planning::ForwardKinematics(setup.sdh, t.trajectory.q.col(c), &sk);
      render::Scene scene;
      AddRobotShapes(setup.sdh, sk, Eigen::Isometry3d::Identity(), opt, &cache_, &scene);
      AddGraspObjectShapes(setup.object, setup.grasp.world_from_object, &scene);
      if (c == 0) camera_ = FrameSceneCamera(scene, view_, 40.0f);
      writer.Add(renderer_.Render(scene, camera_, kFrameWidth, kFrameHeight));
    }
    writer.Finish();
  }

  // Callback for TestGraspStability: a frame every `every` steps of each phase.
  planning::physics::StepCallback Stability(const std::string& dir,
                                            const planning::physics::SimHand& hand,
                                            const planning::physics::SimObject& object,
                                            const planning::physics::StabilityOptions& stab) {
    render::FrameWriterOptions fo;
    fo.prefix = "stability_";
    fo.video = true;
    writer_ = std::make_unique<render::FrameWriter>(dir, fo);
    camera_set_ = false;
    return [this, &hand, &object, stab](int phase, const planning::physics::GraspSimulation& sim) {
      const int every = phase == 0 ? 100 : 250;
      const int step = sim.state().step;
      if (step % every != 0) return;
      Eigen::Vector3d g = Eigen::Vector3d::Zero();
      if (phase > 0) {
        g[(phase - 1) / 2] = ((phase - 1) % 2 == 0 ? 1.0 : -1.0) * stab.gravity;
        g = sim.state().world_from_link[0].linear() * g;
      }
      const render::Scene scene = GraspSimScene(hand, object, sim.state(), g);
      if (!camera_set_) {
        camera_ = FrameSceneCamera(scene, view_, 40.0f);
        camera_set_ = true;
      }
      writer_->Add(renderer_.Render(scene, camera_, kFrameWidth, kFrameHeight));
    };
  }
  void FinishStability() {
    if (writer_) writer_->Finish();
    writer_.reset();
  }

 private:
  render::OffscreenContext context_;
  render::Renderer renderer_;
  SceneMeshCache cache_;
  render::Camera camera_;
  Eigen::Vector3f view_ = Eigen::Vector3f(1.0f, 1.3f, 0.8f);
  bool camera_set_ = false;
  std::unique_ptr<render::FrameWriter> writer_;
};

int RunTransfer(const TransferArgs& a) {
  if (!(a.mu >= 0) || !std::isfinite(a.mu)) {
    throw std::invalid_argument("--mu: must be a finite number >= 0");
  }
  if (a.out_dir.empty()) throw std::invalid_argument("-o: output folder required");
  std::vector<planning::TransferMethod> methods;
  if (a.method == "all") {
    methods = {planning::TransferMethod::kWinding, planning::TransferMethod::kJointMapping,
               planning::TransferMethod::kFingertip};
  } else {
    methods = {planning::ParseTransferMethod(a.method)};
  }
  const std::vector<std::string> files = SelectGraspFiles(a.grasp);
  // Load everything first so that a bad file fails before any simulation runs.
  const std::vector<planning::GraspObject> objects =
      planning::LoadGraspObjects(AssetPath("grasps/objects.json"));
  const planning::Robot human = planning::LoadRobot(AssetPath("robots/human_hand.urdf"));
  const planning::Robot lwr_sdh = planning::LoadRobot(AssetPath("robots/lwr4_sdh.urdf"));
  std::vector<planning::HumanGrasp> grasps;
  for (const std::string& f : files) {
    planning::HumanGrasp g = planning::LoadHumanGrasp(f);
    try {
      planning::FindGraspObject(objects, g.object);
      planning::HumanConfiguration(human, g);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      throw std::invalid_argument(what.rfind(f, 0) == 0 ? what : f + ": " + what);
    }
    grasps.push_back(g);
  }

  planning::physics::OdeRuntime ode;
  std::unique_ptr<GraspFrameWriter> frames;
  if (a.frames) frames = std::make_unique<GraspFrameWriter>();
  planning::physics::StabilityOptions stab;
  stab.sim.mu = a.mu;
  nlohmann::json report;
  report["mu"] = a.mu;
  report["protocol"] = {{"close_time_s", stab.close_time},
                        {"trial_time_s", stab.trial_time},
                        {"dt_s", stab.sim.dt},
                        {"max_slip_m", stab.max_slip},
                        {"max_rotation_deg", stab.max_rotation_deg},
                        {"min_contact_links", stab.min_contact_links}};
  report["grasps"] = nlohmann::json::array();
  std::map<std::string, int> stable_count;
  std::map<std::string, std::vector<double>> passed_series;
  bool all_stable = true;
  for (size_t gi = 0; gi < grasps.size(); ++gi) {
    const planning::HumanGrasp& g = grasps[gi];
    const planning::GraspObject& object = planning::FindGraspObject(objects, g.object);
    const planning::TransferSetup setup = planning::MakeTransferSetup(human, lwr_sdh, object, g);
    nlohmann::json gj;
    gj["name"] = g.name;
    gj["type"] = g.type;
    gj["object"] = g.object;
    gj["file"] = std::filesystem::path(g.source).filename().string();
    nlohmann::json mj = nlohmann::json::object();
    for (planning::TransferMethod m : methods) {
      const planning::TransferResult t = planning::TransferGrasp(setup, m);
      const planning::physics::SimHand hand =
          planning::physics::BuildSimHand(setup.sdh, t.q, "sdh_palm");
      const planning::physics::SimObject body =
          planning::physics::BuildSimObject(object, g.world_from_object);
      planning::physics::StepCallback on_step;
      const std::string frame_dir =
          (std::filesystem::path(a.out_dir) / "frames" / (g.name + "_" + planning::ToString(m)))
              .string();
      if (frames) {
        frames->Transfer(frame_dir + "/transfer", setup, t);
        on_step = frames->Stability(frame_dir + "/stability", hand, body, stab);
      }
      const planning::physics::StabilityResult r =
          planning::physics::TestGraspStability(ode, hand, body, stab, on_step);
      if (frames) frames->FinishStability();
      if (!gj.contains("human_winding")) {
        gj["human_winding"] = VecJson(t.human_winding);
        nlohmann::json hp = nlohmann::json::array();
        for (const Eigen::VectorXd& v : t.human_phalanx_winding) hp.push_back(VecJson(v));
        gj["human_phalanx_winding"] = hp;
      }
      nlohmann::json j;
      j["target_winding"] = VecJson(t.target_winding);
      j["robot_winding"] = VecJson(t.robot_winding);
      nlohmann::json ph = nlohmann::json::array();
      for (const Eigen::VectorXd& v : t.robot_phalanx_winding) ph.push_back(VecJson(v));
      j["robot_phalanx_winding"] = ph;
      j["winding_error"] = Round((t.robot_winding - t.target_winding).norm());
      j["min_clearance_m"] = Round(t.min_clearance);
      j["solver"] = t.solver;
      j["solver_iterations"] = t.iterations;
      j["q"] = VecJson(t.q);
      j["status"] = planning::physics::ToString(r.status);
      j["message"] = r.message;
      j["closure_contact_links"] = r.closure_contact_links;
      j["directions_passed"] = r.directions_passed;
      j["max_slip_m"] = Round(r.max_slip_m);
      j["max_rotation_deg"] = Round(r.max_rotation_deg, 1e3);
      j["stable"] = r.stable;
      nlohmann::json dirs = nlohmann::json::array();
      for (const auto& d : r.directions) {
        dirs.push_back({{"gravity", d.label},
                        {"passed", d.passed},
                        {"slip_m", Round(d.slip_m)},
                        {"rotation_deg", Round(d.rotation_deg, 1e3)},
                        {"contact_links", d.contact_links},
                        {"blown_up", d.blown_up}});
      }
      j["directions"] = dirs;
      mj[planning::ToString(m)] = j;
      stable_count[planning::ToString(m)] += r.stable ? 1 : 0;
      passed_series[planning::ToString(m)].push_back(r.directions_passed);
      all_stable = all_stable && r.stable;
      std::fprintf(stderr, "grasp %-24s %-9s winding err %.3f  clearance %+5.1f mm  %d/6 %s\n",
                   g.name.c_str(), planning::ToString(m),
                   (t.robot_winding - t.target_winding).norm(), t.min_clearance * 1e3,
                   r.directions_passed,
                   r.stable ? "stable" : planning::physics::ToString(r.status));
    }
    gj["methods"] = mj;
    report["grasps"].push_back(gj);
  }
  nlohmann::json summary = nlohmann::json::object();
  for (planning::TransferMethod m : methods) {
    const std::string k = planning::ToString(m);
    summary[k] = {
        {"stable", stable_count[k]},
        {"grasps", grasps.size()},
        {"success_rate",
         Round(static_cast<double>(stable_count[k]) / std::max<size_t>(1, grasps.size()), 1e4)}};
  }
  report["summary"] = summary;

  // summary.md: the success table.
  std::ostringstream md;
  md << "# Grasp transfer to the SDH: ODE stability (mu = " << a.mu << ")\n\n"
     << "Directions passed out of 6 (gravity along +-x, +-y, +-z of the palm, 2 s each at 1 kHz); "
        "a grasp is stable when it passes all 6.\n\n| grasp |";
  for (planning::TransferMethod m : methods) md << " " << planning::ToString(m) << " |";
  md << "\n|---|";
  for (size_t i = 0; i < methods.size(); ++i) md << "---|";
  md << "\n";
  for (const auto& gj : report["grasps"]) {
    md << "| " << gj["name"].get<std::string>() << " |";
    for (planning::TransferMethod m : methods) {
      const auto& j = gj["methods"][planning::ToString(m)];
      md << " " << j["directions_passed"].get<int>() << "/6"
         << (j["stable"].get<bool>() ? " stable" : "") << " |";
    }
    md << "\n";
  }
  md << "| **success rate** |";
  for (planning::TransferMethod m : methods) {
    const std::string k = planning::ToString(m);
    md << " " << stable_count[k] << "/" << grasps.size() << " |";
  }
  md << "\n";

  namespace fs = std::filesystem;
  fs::create_directories(a.out_dir);
  const std::string text = report.dump(1) + "\n";
  WriteFileAtomic((fs::path(a.out_dir) / "report.json").string(), text);
  WriteFileAtomic((fs::path(a.out_dir) / "summary.md").string(), md.str());

  // summary.png: directions passed per grasp, one marker series per method.
  std::vector<render::PlotSeries> series;
  const render::Marker markers[3] = {render::Marker::kCircle, render::Marker::kSquare,
                                     render::Marker::kTriangle};
  for (size_t mi = 0; mi < methods.size(); ++mi) {
    const std::string k = planning::ToString(methods[mi]);
    render::PlotSeries ps;
    std::ostringstream label;
    label << k << " (" << stable_count[k] << "/" << grasps.size() << " stable)";
    ps.label = label.str();
    for (size_t gi = 0; gi < grasps.size(); ++gi) {
      ps.x.push_back(static_cast<double>(gi + 1) + 0.12 * (static_cast<double>(mi) - 1.0));
      ps.y.push_back(passed_series[k][gi]);
    }
    ps.line = false;
    ps.marker = markers[mi % 3];
    series.push_back(ps);
  }
  render::PlotOptions po;
  po.width = 900;
  po.height = 560;
  po.title =
      "SDH grasp transfer: gravity directions held (mu " + std::to_string(a.mu).substr(0, 4) + ")";
  po.x_label = "grasp (row of summary.md)";
  po.y_label = "directions held";
  po.x_min = 0.5;
  po.x_max = grasps.size() + 0.5;
  po.y_min = -0.5;
  po.y_max = 7.5;
  po.legend = render::LegendPosition::kTopLeft;
  render::WriteFileAtomically((fs::path(a.out_dir) / "summary.png").string(),
                              render::EncodePng(render::RenderPlot(series, po)));

  if (a.json) std::cout << text;
  std::fprintf(stderr, "wrote %s/report.json, summary.md, summary.png\n", a.out_dir.c_str());
  return all_stable ? kExitOk : kExitFailed;
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
  commands->push_back({synth, [sa] { return RunSynthesize(*sa); }});

  auto ta = std::make_shared<TransferArgs>();
  CLI::App* transfer = grasp->add_subcommand(
      "transfer",
      "Transfer human grasps (assets/grasps/*.json) to the Schunk SDH by winding numbers (AICO) "
      "and by the joint-mapping and fingertip-mapping baselines, then test each transferred "
      "grasp in ODE: close with gravity off, then gravity along the 6 palm axes for 2 s each. "
      "Writes DIR/report.json, DIR/summary.md, DIR/summary.png. Exit 0 if every tested grasp is "
      "stable, 1 if some is not, 2 for bad input.");
  transfer
      ->add_option("--grasp", ta->grasp, "grasp name (file stem in assets/grasps), a path, or all")
      ->capture_default_str();
  transfer->add_option("--method", ta->method, "winding | joint | fingertip | all")
      ->capture_default_str();
  transfer->add_option("--mu", ta->mu, "Coulomb friction coefficient (friction pyramid)")
      ->capture_default_str();
  transfer->add_option("-o,--output", ta->out_dir, "output folder")->required();
  transfer->add_flag("--frames", ta->frames,
                     "also write frames of the transfer and stability test");
  transfer->add_flag("--json", ta->json, "print report.json to stdout");
  commands->push_back({transfer, [ta] { return RunTransfer(*ta); }});
}

}  // namespace app
