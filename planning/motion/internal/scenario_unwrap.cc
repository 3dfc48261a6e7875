// `scenario new --task unwrap` (internal/scenario_unwrap.h).
#include "planning/motion/internal/scenario_unwrap.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <random>
#include <stdexcept>

#include "base/assets.h"
#include "base/numbers.h"
#include "base/random.h"
#include "base/str_cat.h"
#include "planning/collision/collision.h"
#include "planning/motion/internal/scenario_file.h"
#include "planning/robot/kinematics.h"
#include "planning/robot/pose.h"
#include "planning/robot/robot_io.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace planning::internal {
namespace {

namespace fs = std::filesystem;

constexpr int kSamples = 1500;            // seeded random arm configurations
constexpr double kMinHookWrithe = 0.15;   // |total writhe| of the start, turns (3 × success 0.05)
constexpr double kGoalWrithe = 0.02;      // |total writhe| of the goal, turns
constexpr double kGoalWinding = 0.05;     // |winding| of the goal about the pole's line, turns
constexpr double kLineClearance = 0.1;    // every arm chain segment this far from the pole's axis
constexpr int kMaxHooks = 40;             // hooks tried (largest winding first) for a goal
constexpr double kFloorClearance = 0.05;  // arm points this far above the floor, m

// Distance (m) between the segment [a, b] and the line through p along the unit vector d.
double SegmentLineDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                           const Eigen::Vector3d& p, const Eigen::Vector3d& d) {
  Eigen::Vector3d u = a - p, v = b - p;
  u -= d * d.dot(u);
  v -= d * d.dot(v);
  const Eigen::Vector3d e = v - u;
  const double ee = e.squaredNorm();
  const double t = ee > 0.0 ? std::clamp(-u.dot(e) / ee, 0.0, 1.0) : 0.0;
  return (u + t * e).norm();
}

double LineClearance(const Eigen::Matrix3Xd& p, const Eigen::Vector3d& point,
                     const Eigen::Vector3d& dir) {
  double d = INFINITY;
  for (Eigen::Index i = 0; i + 1 < p.cols(); ++i)
    d = std::min(d, SegmentLineDistance(p.col(i), p.col(i + 1), point, dir));
  return d;
}

// The centre of a link's collision geometry in its frame (the mean of its shapes' centres, a
// mesh's centre the mean of its vertices); nullopt without collision geometry.
std::optional<Eigen::Vector3d> GeometryCentre(const Robot& robot, int link) {
  const std::vector<Geometry>& shapes = robot.links[link].collisions;
  if (shapes.empty()) return std::nullopt;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Geometry& g : shapes) {
    Eigen::Vector3d local = Eigen::Vector3d::Zero();
    if (g.kind == Geometry::Kind::kMesh && g.mesh >= 0) {
      const Mesh& mesh = robot.meshes[g.mesh];
      for (const Eigen::Vector3f& v : mesh.vertices) local += v.cast<double>();
      if (!mesh.vertices.empty()) local /= static_cast<double>(mesh.vertices.size());
      local = local.cwiseProduct(g.size);
    }
    sum += g.link_from_geometry * local;
  }
  return sum / static_cast<double>(shapes.size());
}

// The arm chain, inside the arm's body: for each link of the path from the first arm joint to the
// hand, its origin (the joint) and the centre of its collision geometry; a point within 1 cm of
// the previous one replaces it. Each segment then runs from a joint into the link it moves, or
// from a link's centre to its next joint, through the link's body (as far as the link is convex),
// so the chain cannot cross the pole's axis where the arm does not touch the pole. Link origins
// alone are not enough (offset joints leave segments in free space), nor is the tool point (a
// gripper straddles a pole with its fingers).
LinkPoints ArmChain(const Robot& robot, const ArmSetup& s, const KinematicsData& kin) {
  LinkPoints chain;
  const auto add = [&](int link, const Eigen::Vector3d& xyz) {
    if (!chain.empty()) {
      const Eigen::Vector3d last = kin.world_from_link[chain.back().first] * chain.back().second;
      if ((kin.world_from_link[link] * xyz - last).norm() < 0.01) {
        chain.back() = {link, xyz};
        return;
      }
    }
    chain.emplace_back(link, xyz);
  };
  const auto first = std::find(s.arm.path.begin(), s.arm.path.end(), s.arm_links.front());
  for (auto it = first; it != s.arm.path.end(); ++it) {
    add(*it, Eigen::Vector3d::Zero());
    if (const auto centre = GeometryCentre(robot, *it)) add(*it, *centre);
  }
  return chain;
}

// A pole line the chain `p` winds about: along the normal of the chain's best-fit plane, through
// the point of a 9 × 9 grid over the chain's extent in that plane with the largest |winding|
// among those kLineClearance from every segment. winding = 0 when none is.
struct Hook {
  int sample = -1;
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), dir = Eigen::Vector3d::UnitZ();
  double winding = 0.0, writhe = 0.0;
};

Hook BestHook(const Eigen::Matrix3Xd& p) {
  Hook best;
  const Eigen::Vector3d c = p.rowwise().mean();
  const Eigen::Matrix3Xd centred = p.colwise() - c;
  // Principal axes from the 3 × 3 scatter matrix (its eigenvalues, ascending, are the squared
  // singular values of `centred`). An SVD of the 3 × N matrix gives the same axes but took 20 s of
  // the build to compile.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(centred * centred.transpose());
  const Eigen::Vector3d sv = eig.eigenvalues().reverse().cwiseMax(0.0).cwiseSqrt();
  if (sv[1] < 0.05 * sv[0]) return best;  // a straight chain winds about nothing
  const Eigen::Vector3d e1 = eig.eigenvectors().col(2), e2 = eig.eigenvectors().col(1);
  const Eigen::Vector3d n = e1.cross(e2);  // right-handed frame
  const double ext1 = (e1.transpose() * centred).cwiseAbs().maxCoeff();
  const double ext2 = (e2.transpose() * centred).cwiseAbs().maxCoeff();
  for (int a = -4; a <= 4; ++a) {
    for (int b = -4; b <= 4; ++b) {
      const Eigen::Vector3d point = c + e1 * (0.2 * a * ext1) + e2 * (0.2 * b * ext2);
      if (LineClearance(p, point, n) < kLineClearance) continue;
      const double w = topology::WindingNumber(p, topology::Axis{point, n});
      if (std::abs(w) > std::abs(best.winding)) {
        best.point = point;
        best.dir = n;
        best.winding = w;
      }
    }
  }
  return best;
}

Eigen::Isometry3d PolePose(const Hook& h) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = h.point;
  pose.linear() = RotationFromZ(h.dir);
  return pose;
}

}  // namespace

NewScenario MakeUnwrapScenario(const RobotScene& scene, const std::string& urdf,
                               const NewScenarioOptions& o, const ArmSetup& s, NewScenario out) {
  const Robot& robot = scene.robot;
  out.hand_link = robot.links[s.arm.hand].name;
  KinematicsData kin(robot);
  ForwardKinematics(robot, s.q0, &kin);
  const LinkPoints chain = ArmChain(robot, s, kin);
  if (chain.size() < 3) {
    throw std::invalid_argument(base::StrCat(urdf, ": the arm to '", out.hand_link,
                                             "' has fewer than 3 distinct points; it cannot wrap "
                                             "a pole (name another hand with --hand)"));
  }
  const std::string pole_path = o.object.empty() ? base::AssetPath("objects/pole.urdf") : o.object;
  const Robot pole = LoadRobot(pole_path);
  const int axis_chain = FindChain(pole, "axis");

  // Seeded samples of the arm joints inside the limits (revolute joints min(0.1, ¼ range) rad
  // inside, unbounded ones ±π around the start), the other joints at the start; self-collision
  // free ones are kept.
  std::mt19937 rng(o.seed);
  std::vector<Eigen::VectorXd> samples;
  std::vector<Eigen::Matrix3Xd> points;
  // The floor: the lowest link origin in the start pose (a fixed base's root, a humanoid's feet;
  // URDFs are z-up); arm points stay kFloorClearance above it.
  double floor_z = INFINITY;
  for (size_t l = 0; l < robot.links.size(); ++l)
    floor_z = std::min(floor_z, Origin(kin, static_cast<int>(l)).z());
  int self_colliding = 0, below_floor = 0;
  {
    CollisionData self(robot, Environment{}, s.collision_options);
    for (int i = 0; i < kSamples; ++i) {
      Eigen::VectorXd q = s.q0;
      for (int k : s.arm.arm_dofs) {
        const bool prismatic = robot.joints[robot.dof_joints[k]].type == JointType::kPrismatic;
        double lo = std::isfinite(s.lower[k]) ? s.lower[k] : s.q0[k] - M_PI;
        double hi = std::isfinite(s.upper[k]) ? s.upper[k] : s.q0[k] + M_PI;
        const double room = prismatic ? 0.0 : std::min(0.1, 0.25 * (hi - lo));
        lo += room;
        hi -= room;
        q[k] = lo + base::UniformUnit(&rng) * (hi - lo);
      }
      ForwardKinematics(robot, q, &kin);
      Eigen::Matrix3Xd p = WorldPoints(chain, kin);
      if (p.row(2).minCoeff() < floor_z + kFloorClearance) {
        ++below_floor;
        continue;
      }
      if (InCollision(robot, kin, &self)) {
        ++self_colliding;
        continue;
      }
      samples.push_back(q);
      points.push_back(std::move(p));
    }
  }
  // Hooks: per sample the best pole line, largest |winding| first.
  std::vector<Hook> hooks;
  for (size_t i = 0; i < samples.size(); ++i) {
    Hook h = BestHook(points[i]);
    if (std::abs(h.winding) < kMinHookWrithe) continue;
    h.sample = static_cast<int>(i);
    hooks.push_back(h);
  }
  std::stable_sort(hooks.begin(), hooks.end(), [](const Hook& a, const Hook& b) {
    return std::abs(a.winding) > std::abs(b.winding);
  });
  // The first hook whose pole clears the arm, whose writhe is large enough and for which an
  // unwrapped goal exists among the samples: the goal nearest the start in joint space.
  int tried = 0, pole_hits = 0, small_writhe = 0, no_goal = 0;
  Hook chosen;
  int goal = -1;
  for (const Hook& hook : hooks) {
    if (tried++ == kMaxHooks) break;
    Environment env;
    AddObject(pole, PolePose(hook), "pole", &env);
    CollisionData coll(robot, env, s.collision_options);
    ForwardKinematics(robot, samples[hook.sample], &kin);
    if (InCollision(robot, kin, &coll)) {
      ++pole_hits;
      continue;
    }
    const Eigen::Matrix3Xd axis = ObjectChainPoints(env, 0, axis_chain);
    const double writhe = topology::TotalWrithe(points[hook.sample], axis);
    if (std::abs(writhe) < kMinHookWrithe) {
      ++small_writhe;
      continue;
    }
    const Eigen::Vector3d line_point = axis.col(0);
    const Eigen::Vector3d line_dir = (axis.col(axis.cols() - 1) - axis.col(0)).normalized();
    double best = INFINITY;
    for (size_t j = 0; j < samples.size(); ++j) {
      const double dist = (samples[j] - samples[hook.sample]).norm();
      if (dist >= best) continue;
      if (LineClearance(points[j], line_point, line_dir) < kLineClearance) continue;
      if (std::abs(topology::WindingNumber(points[j], topology::Axis{line_point, line_dir})) >=
          kGoalWinding) {
        continue;
      }
      if (std::abs(topology::TotalWrithe(points[j], axis)) >= kGoalWrithe) continue;
      ForwardKinematics(robot, samples[j], &kin);
      if (InCollision(robot, kin, &coll)) continue;
      best = dist;
      goal = static_cast<int>(j);
    }
    if (goal < 0) {
      ++no_goal;
      continue;
    }
    chosen = hook;
    chosen.writhe = writhe;
    break;
  }
  if (goal < 0) {
    throw std::invalid_argument(base::StrCat(
        urdf, ": no start hooked around the pole found for hand '", out.hand_link, "' (",
        std::to_string(kSamples), " seeded samples: ", std::to_string(below_floor),
        " below the floor, ", std::to_string(self_colliding), " self-colliding, ",
        std::to_string(hooks.size()), " winding ≥ ", base::FormatShortest(kMinHookWrithe),
        " turns about a line ", base::FormatShortest(kLineClearance), " m clear of the arm; of ",
        std::to_string(tried), " tried: ", std::to_string(pole_hits), " touch the pole, ",
        std::to_string(small_writhe), " writhe too small, ", std::to_string(no_goal),
        " without an unwrapped goal); try --seed or --hand"));
  }
  out.start_q = samples[chosen.sample];
  out.goal_q = samples[goal];
  ForwardKinematics(robot, out.goal_q, &kin);
  out.tool_target = kin.world_from_link[s.arm.hand] * s.tool_local;
  out.ring_center = chosen.point;
  const Eigen::Isometry3d pole_pose = PolePose(chosen);
  out.notes.push_back(base::StrCat(
      "start: a sampled pose hooked around the pole, winding ",
      base::FormatShortest(std::round(chosen.winding * 360.0)), "°, total writhe ",
      base::FormatShortest(std::round(chosen.writhe * 1000.0) / 1000.0), " (",
      std::to_string(samples.size()), " samples above the floor and free of self-collision, of ",
      std::to_string(kSamples), ")"));
  out.notes.push_back(base::StrCat(
      "goal: the unwrapped sample nearest the start (",
      base::FormatShortest(std::round((out.goal_q - out.start_q).norm() * 1000.0) / 1000.0),
      " rad away); its tool point is the reach target"));

  // The file. The chain is "arm" unless the robot has a chain of that name.
  std::string chain_name = "arm";
  while (std::any_of(robot.chains.begin(), robot.chains.end(),
                     [&](const auto& c) { return c.name == chain_name; })) {
    chain_name += "_wrap";
  }
  Json j = ScenarioHead(
      scene, urdf, o, s,
      base::StrCat("Made by `topoplan scenario new --task unwrap` for robot '", robot.name,
                   "': the arm starts hooked around a pole and must unwrap (total writhe arm x "
                   "pole -> 0) while the tool point of hand '",
                   out.hand_link, "' reaches a target. Keys starting with // are comments."),
      chain_name, chain,
      "the arm chain: each arm link's origin (its joint) and the centre of its collision "
      "geometry, to the hand (its writhe about the pole is what unwraps)");
  j["// objects"] =
      "the pole: move or tilt it with xyz/rpy (its axis is its local z); the start hook and "
      "the goal were found for this placement";
  j["objects"] = Json::array({{{"name", "pole"},
                               {"urdf", fs::absolute(pole_path).lexically_normal().string()},
                               {"xyz", Vec(pole_pose.translation())},
                               {"rpy", RpyJson(pole_pose.linear())}}});
  j["writhe_report"] = {{"chain", chain_name}, {"object", "pole"}, {"object_chain", "axis"}};
  j["// start"] = "a sampled pose hooked around the pole (see the description)";
  j["start"] = {{"q", QJson(out.start_q)}};
  j["problem"] = {
      {"T", 50}, {"duration", 2.0}, {"dynamic", true}, {"h_rate", 1.0}, {"w_rate", 1.0}};
  Json tasks = Json::array();
  tasks.push_back({{"name", "writhe"},
                   {"feature",
                    {{"type", "writhe"},
                     {"chain", chain_name},
                     {"object", "pole"},
                     {"object_chain", "axis"},
                     {"output", "total"}}},
                   {"target", {{"type", "interpolate"}, {"value", 0}}},
                   {"precision", 1000},
                   {"final_precision", 30000}});
  tasks.push_back({{"name", "collision"},
                   {"feature", {{"type", "collision"}, {"margin", 0.02}}},
                   {"precision", 100},
                   {"between", 1}});
  tasks.push_back({{"name", "off_pole_line"},
                   {"feature",
                    {{"type", "line_clearance"},
                     {"chain", chain_name},
                     {"object", "pole"},
                     {"object_chain", "axis"},
                     {"margin", kLineClearance}}},
                   {"precision", 1000},
                   {"between", 1}});
  tasks.push_back(
      {{"name", "winding_guard"},
       {"feature",
        {{"type", "winding"}, {"chain", chain_name}, {"object", "pole"}, {"object_chain", "axis"}}},
       {"precision", 0},
       {"between", 3},
       {"max_jump", 0.2}});
  tasks.push_back(LimitsTask(0.1, 10000));
  tasks.push_back(
      {{"name", "reach"},
       {"feature", {{"type", "position"}, {"link", out.hand_link}, {"offset", Vec(s.tool_local)}}},
       {"target", {{"type", "interpolate"}, {"value", Vec(out.tool_target)}}},
       {"precision", 1},
       {"final_precision", 10000}});
  tasks.push_back(QdotTask());
  j["tasks"] = tasks;
  j["// final_pose"] = "init: the unwrapped goal sample, all joints in fk order";
  j["final_pose"] = {{"tasks", Json::array({"reach", "writhe", "collision", "limits"})},
                     {"init", QJson(out.goal_q)},
                     {"alpha", 0.05}};
  j["success"] = {{"writhe_total_below", 0.05},
                  {"position", {{"task", "reach"}, {"tolerance", 0.05}}},
                  {"winding", {{"max_jump", 0.1}, {"final_below", 0.1}}}};
  j["aico"] = {{"max_iterations", 40}, {"tolerance", 0.01},
               {"damping", 10.0},      {"sweep_mode", "local_gauss_newton"},
               {"max_relocations", 5}, {"relocation_damping", 0.3},
               {"max_step", 0.3},      {"rollout_init", true},
               {"rollout_prior", 300}, {"stop_when_solved", true}};
  j["rrt"] = {{"range", 0.5}, {"resolution", 0.02}, {"goal_bias", 0.1}, {"max_checks", 100000}};
  j["check_resolution"] = 0.02;
  out.json = std::move(j);
  return out;
}

}  // namespace planning::internal
