// Noisy demonstrations (planning/grasp/demo_noise.h).
#include "planning/grasp/demo_noise.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "base/random.h"
#include "planning/robot/kinematics.h"

namespace planning {
namespace {

std::uint64_t NameHash(const std::string& name) {  // FNV-1a 64
  std::uint64_t h = 14695981039346656037ull;
  for (unsigned char c : name) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

constexpr int kMaxBackOffSteps = 40;    // RecloseDemonstration: at most 4 cm
constexpr double kBackOffStep = 0.001;  // [m]

bool IsPalmDof(const std::string& name) { return name.rfind("hand_", 0) == 0; }

double JointValue(const HumanGrasp& g, const std::string& name) {
  const auto it = g.joints.find(name);
  return it == g.joints.end() ? 0.0 : it->second;
}

}  // namespace

HumanGrasp NoisyDemonstration(const Robot& human, const HumanGrasp& nominal, int index,
                              const DemoNoiseOptions& o) {
  if (index < 0) throw std::invalid_argument("noisy demonstration: index must be >= 0");
  for (double v : {o.joint_deg, o.palm_translation, o.palm_rotation_deg}) {
    if (!(v >= 0) || !std::isfinite(v)) {
      throw std::invalid_argument("noisy demonstration: noise bounds must be finite and >= 0");
    }
  }
  const std::vector<std::string> names = DofNames(human);
  for (const auto& [name, value] : nominal.joints) {
    if (std::find(names.begin(), names.end(), name) == names.end()) {
      throw std::invalid_argument(nominal.source + ": joints." + name +
                                  ": not a joint of the human hand model");
    }
  }
  const std::uint64_t h = NameHash(nominal.name);
  std::seed_seq seq{o.seed, static_cast<std::uint32_t>(h), static_cast<std::uint32_t>(h >> 32),
                    static_cast<std::uint32_t>(index)};
  std::mt19937 rng(seq);
  auto symmetric = [&rng](double a) { return a * (2.0 * base::UniformUnit(&rng) - 1.0); };

  HumanGrasp demo = nominal;
  demo.name = nominal.name;
  demo.name.push_back('#');
  demo.name.append(std::to_string(index));
  const double joint_bound = o.joint_deg * M_PI / 180.0;
  for (size_t k = 0; k < names.size(); ++k) {
    if (IsPalmDof(names[k])) continue;
    const JointLimits& lim = human.joints[human.dof_joints[k]].limits;
    const double v = JointValue(nominal, names[k]) + symmetric(joint_bound);
    demo.joints[names[k]] = std::clamp(v, lim.lower, lim.upper);
  }
  Eigen::Vector3d t;
  for (int i = 0; i < 3; ++i) t[i] = symmetric(o.palm_translation);
  const Eigen::Vector3d axis = base::UniformUnitVector(&rng);
  const double angle = symmetric(o.palm_rotation_deg * M_PI / 180.0);
  Eigen::Isometry3d palm = nominal.world_from_palm;
  palm.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix() * palm.linear();
  palm.translation() += t;
  demo.world_from_palm = palm;
  return demo;
}

double RecloseDemonstration(const Robot& human, const GraspObject& object, HumanGrasp* demo) {
  if (demo->close.empty()) return std::numeric_limits<double>::infinity();
  // The palm backs away from the object (+y_palm: the palm faces −y) until it clears it.
  const int palm = FindLink(human, "hand_palm");
  const HandSpheres spheres = SampleHandSpheres(human, {palm}, 0.003);
  KinematicsData kin(human);
  for (int k = 0; k < kMaxBackOffSteps; ++k) {
    ForwardKinematics(human, HumanConfiguration(human, *demo), &kin);
    if (HandClearance(human, kin, spheres, object, demo->world_from_object) >= 0) break;
    demo->world_from_palm.translation() += kBackOffStep * demo->world_from_palm.linear().col(1);
  }
  const double clearance = SynthesizeGrasp(human, object, demo);
  demo->close.clear();
  return clearance;
}

DemoDeviation MeasureDeviation(const Robot& human, const HumanGrasp& nominal,
                               const HumanGrasp& demo) {
  DemoDeviation d;
  for (const std::string& name : DofNames(human)) {
    if (IsPalmDof(name)) continue;
    d.joint = std::max(d.joint, std::abs(JointValue(demo, name) - JointValue(nominal, name)));
  }
  d.palm_translation = (demo.world_from_palm.translation() - nominal.world_from_palm.translation())
                           .cwiseAbs()
                           .maxCoeff();
  d.palm_rotation = Eigen::AngleAxisd(demo.world_from_palm.linear() *
                                      nominal.world_from_palm.linear().transpose())
                        .angle();
  return d;
}

}  // namespace planning
