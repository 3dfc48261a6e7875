// `topoplan grasp synthesize` and `topoplan grasp transfer`: human grasps, their winding encoding,
// transfer to the Schunk SDH and the ODE stability test.
#include <cstdio>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/assets.h"
#include "app/command.h"
#include "app/io.h"
#include "planning/grasp.h"
#include "planning/grasp_object.h"
#include "planning/kinematics.h"
#include "planning/robot_io.h"

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
}

}  // namespace app
