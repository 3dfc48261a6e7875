// Grasp transfer to the SDH (planning/grasp/grasp_transfer.h): the floating hand, the setup and
// placement, the shared and per-method tasks, and the multi-start AICO runs. The transfer's own
// features are in planning/grasp/internal/ (grasp winding, hand-sphere clearance, palm pose).
#include "planning/grasp/grasp_transfer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "planning/features/feature.h"
#include "planning/features/task.h"
#include "planning/grasp/internal/clearance_feature.h"
#include "planning/grasp/internal/grasp_winding_feature.h"
#include "planning/grasp/internal/palm_pose_feature.h"
#include "planning/robot/kinematics.h"

namespace planning {
namespace {

using internal::ClearanceFeature;
using internal::GraspWindingFeature;
using internal::PalmPoseFeature;

// Task active only at the last slice (precision ρ at t = T, 0 before).
Task FinalTask(const std::string& name, std::unique_ptr<Feature> f, const Eigen::VectorXd& y,
               double precision, int T) {
  Task task;
  task.name = name;
  task.feature = std::move(f);
  task.target = y.replicate(1, T + 1);
  task.precision = Eigen::VectorXd::Zero(T + 1);
  task.precision[T] = precision;
  return task;
}

Task ConstantTask(const std::string& name, std::unique_ptr<Feature> f, const Eigen::VectorXd& y,
                  double precision, int T) {
  Task task;
  task.name = name;
  task.feature = std::move(f);
  SetConstantTarget(&task, y, precision, T);
  return task;
}

double Clamp(const Robot& robot, int dof, double v) {
  const JointLimits& l = robot.joints[robot.dof_joints[dof]].limits;
  return std::clamp(v, l.lower, l.upper);
}

int Dof(const Robot& robot, const std::string& joint) {
  const std::vector<std::string> names = DofNames(robot);
  const auto it = std::find(names.begin(), names.end(), joint);
  if (it == names.end()) throw std::invalid_argument("no joint '" + joint + "' in " + robot.name);
  return static_cast<int>(it - names.begin());
}

double HumanAngle(const HumanGrasp& g, const std::string& name) {
  const auto it = g.joints.find(name);
  return it == g.joints.end() ? 0.0 : it->second;
}

// Links of `robot` whose names start with `prefix` (finger links of one SDH finger).
std::vector<int> LinksWithPrefix(const Robot& robot, const std::string& prefix) {
  std::vector<int> out;
  for (size_t i = 0; i < robot.links.size(); ++i) {
    if (robot.links[i].name.rfind(prefix, 0) == 0) out.push_back(static_cast<int>(i));
  }
  return out;
}

// SDH finger link prefixes: thumb, finger_1, finger_2.
const char* const kSdhFingers[3] = {"sdh_thumb", "sdh_finger_1", "sdh_finger_2"};

// Linear joint mapping (Rohling et al. 1993) with the finger correspondence: per SDH finger the
// proximal joint = mean of the corresponding human proximal flexions, the distal joint = mean of
// the distal ones (clamped to the limits); other dofs of q_place unchanged.
Eigen::VectorXd JointMapping(const TransferSetup& s, const Eigen::VectorXd& q_place) {
  const HumanGrasp& g = s.grasp;
  auto mean = [](std::initializer_list<double> v) {
    double sum = 0;
    for (double x : v) sum += x;
    return sum / static_cast<double>(v.size());
  };
  const double prox[3] = {
      mean({HumanAngle(g, "thumb_cmc_flex"), HumanAngle(g, "thumb_mcp")}),
      mean({HumanAngle(g, "ring_mcp_flex"), HumanAngle(g, "little_mcp_flex")}),
      mean({HumanAngle(g, "index_mcp_flex"), HumanAngle(g, "middle_mcp_flex")})};
  const double dist[3] = {HumanAngle(g, "thumb_ip"),
                          mean({HumanAngle(g, "ring_pip"), HumanAngle(g, "ring_dip"),
                                HumanAngle(g, "little_pip"), HumanAngle(g, "little_dip")}),
                          mean({HumanAngle(g, "index_pip"), HumanAngle(g, "index_dip"),
                                HumanAngle(g, "middle_pip"), HumanAngle(g, "middle_dip")})};
  Eigen::VectorXd q = q_place;
  for (int f = 0; f < 3; ++f) {
    const int p = Dof(s.sdh, std::string(kSdhFingers[f]) + "_proximal_joint");
    const int d = Dof(s.sdh, std::string(kSdhFingers[f]) + "_distal_joint");
    q[p] = Clamp(s.sdh, p, prox[f]);
    q[d] = Clamp(s.sdh, d, dist[f]);
  }
  return q;
}

// --- MakeFloatingHand's parts
// ---------------------------------------------------------------------

// Per link of `source`: 1 if it is `root` or below it (links come in topological order).
std::vector<char> SubtreeMask(const Robot& source, int root) {
  std::vector<char> in(source.links.size(), 0);
  in[root] = 1;
  for (size_t i = 0; i < source.links.size(); ++i) {
    const int pj = source.links[i].parent_joint;
    if (pj >= 0 && in[source.joints[pj].parent_link]) in[i] = 1;
  }
  return in;
}

// Appends the "world" link and the 6 floating joints (hand_tx, hand_ty, hand_tz prismatic along the
// world axes within ±5 m, then hand_rz, hand_ry, hand_rx continuous, hand_rz's frame rotated by
// `nominal`) to the empty `out`, dofs 0..5; the last one carries source link `root`, whose new
// index goes to (*new_index)[root].
void AddFloatingJoints(const Robot& source, int root, const Eigen::Matrix3d& nominal, Robot* out,
                       std::vector<int>* new_index) {
  Link world;
  world.name = "world";
  out->links.push_back(world);
  const char* names[6] = {"hand_tx", "hand_ty", "hand_tz", "hand_rz", "hand_ry", "hand_rx"};
  const Eigen::Vector3d axes[6] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                                   Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()};
  for (int k = 0; k < 6; ++k) {
    Joint j;
    j.name = names[k];
    j.type = k < 3 ? JointType::kPrismatic : JointType::kContinuous;
    j.parent_link = static_cast<int>(out->links.size()) - 1;
    j.child_link = static_cast<int>(out->links.size());
    if (k == 3) j.parent_from_joint.linear() = nominal;
    j.axis = axes[k];
    if (k < 3) {
      j.limits.lower = -5.0;
      j.limits.upper = 5.0;
    }
    j.dof = k;
    Link child;
    if (k < 5) {
      child.name = std::string("float_") + names[k];
    } else {
      child = source.links[root];
      (*new_index)[root] = j.child_link;
    }
    child.parent_joint = static_cast<int>(out->joints.size());
    out->joints.push_back(j);
    out->dof_joints.push_back(static_cast<int>(out->joints.size()) - 1);
    out->links.push_back(child);
  }
}

// Appends the links below `root` (mask `in`) with their parent joints to `out`, in the source's
// topological order; their dofs are renumbered from 6 in the source dof order (mimic joints keep
// their masters) and appended to out->dof_joints by new dof. Fills (*new_index)[link].
void CopySubtree(const Robot& source, int root, const std::vector<char>& in, Robot* out,
                 std::vector<int>* new_index) {
  std::vector<int> new_dof(source.dof_joints.size(), -1);
  for (size_t k = 0; k < source.dof_joints.size(); ++k) {
    const Joint& j = source.joints[source.dof_joints[k]];
    if (in[j.child_link] && j.child_link != root) {
      new_dof[k] = 6 + static_cast<int>(std::count_if(new_dof.begin(), new_dof.begin() + k,
                                                      [](int v) { return v >= 0; }));
    }
  }
  std::vector<std::pair<int, int>> dof_order;  // (new dof, new joint index)
  for (size_t i = 0; i < source.links.size(); ++i) {
    if (!in[i] || static_cast<int>(i) == root) continue;
    const Joint& sj = source.joints[source.links[i].parent_joint];
    Joint j = sj;
    j.parent_link = (*new_index)[sj.parent_link];
    j.child_link = static_cast<int>(out->links.size());
    if (j.dof >= 0) {
      j.dof = new_dof[j.dof];
      if (j.dof < 0) {
        throw std::invalid_argument("MakeFloatingHand: joint '" + sj.name +
                                    "' follows a joint outside the subtree");
      }
    }
    Link l = source.links[i];
    l.parent_joint = static_cast<int>(out->joints.size());
    (*new_index)[i] = j.child_link;
    out->joints.push_back(j);
    if (j.dof >= 0 && !j.is_mimic) dof_order.push_back({j.dof, l.parent_joint});
    out->links.push_back(l);
  }
  std::sort(dof_order.begin(), dof_order.end());
  for (const auto& [dof, joint] : dof_order) out->dof_joints.push_back(joint);
}

}  // namespace

Eigen::VectorXd WindingTarget(const TransferSetup& s, bool main_only) {
  KinematicsData hkin(s.human);
  ForwardKinematics(s.human, s.human_q, &hkin);
  const int ne = main_only ? 0 : static_cast<int>(s.extra_references.size());
  const int nm = main_only || s.object.main_reference_in_target ? 3 : 0;
  Eigen::VectorXd y(nm + 2 * ne);
  if (nm > 0) {
    y.head(3) =
        FingerCorrespondence() * EncodeGrasp(s.human, hkin, s.human_chains, s.reference).finger;
  }
  for (int r = 0; r < ne; ++r) {
    y.segment<2>(nm + 2 * r) =
        OppositionPair(EncodeGrasp(s.human, hkin, s.human_chains, s.extra_references[r]).finger);
  }
  return y;
}

Eigen::MatrixXd FingerCorrespondence() {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(3, 5);
  m(0, 0) = 1.0;            // SDH thumb    ← thumb
  m(1, 3) = m(1, 4) = 0.5;  // SDH finger_1 ← ring, little (ulnar side)
  m(2, 1) = m(2, 2) = 0.5;  // SDH finger_2 ← index, middle (radial side)
  return m;
}

Robot MakeFloatingHand(const Robot& source, const std::string& root_link,
                       const Eigen::Matrix3d& nominal) {
  const int root = FindLink(source, root_link);
  const std::vector<char> in = SubtreeMask(source, root);
  Robot out;
  out.name = source.name + "/" + root_link + " (floating)";
  out.source = source.source;
  out.meshes = source.meshes;
  std::vector<int> new_index(source.links.size(), -1);
  AddFloatingJoints(source, root, nominal, &out, &new_index);
  CopySubtree(source, root, in, &out, &new_index);
  // Chains whose points all lie in the subtree.
  for (const ChainSpec& c : source.chains) {
    bool inside = true;
    for (int li : c.point_link) inside = inside && in[li];
    if (!inside) continue;
    ChainSpec nc = c;
    for (int& li : nc.point_link) li = new_index[li];
    out.chains.push_back(nc);
  }
  return out;
}

TransferSetup MakeTransferSetup(const Robot& human_hand, const Robot& sdh_source,
                                const GraspObject& object, const HumanGrasp& grasp,
                                PlacementRule rule) {
  TransferSetup s;
  s.human = human_hand;
  s.human_chains = AddGraspChains(true, &s.human);
  s.object = object;
  s.grasp = grasp;
  s.reference = TransformReference(object.reference, grasp.world_from_object);
  for (const ReferenceCurve& extra : object.extra_references) {
    s.extra_references.push_back(TransformReference(extra, grasp.world_from_object));
  }
  s.human_q = HumanConfiguration(s.human, grasp);
  KinematicsData kin(s.human);
  ForwardKinematics(s.human, s.human_q, &kin);
  const Eigen::Isometry3d palm = kin.world_from_link[FindLink(s.human, "hand_palm")];
  const Eigen::Vector3d xh = palm.linear().col(0), yh = palm.linear().col(1);
  Eigen::Matrix3d r;
  r.col(2) = -yh;
  r.col(1) = -xh;
  r.col(0) = r.col(1).cross(r.col(2));
  // Grasp centre: the reference point nearest to the human palm centre (axis) or the loop's
  // centroid; the SDH palm is placed on the line through it along z_SDH, far enough back that
  // the knuckles clear the object by 5 mm.
  const Eigen::Vector3d palm_centre = palm * Eigen::Vector3d(0, -0.014, 0.045);
  s.sdh = MakeFloatingHand(sdh_source, "sdh_palm", r);
  s.sdh_chains = AddGraspChains(false, &s.sdh);
  s.sdh_placement = Eigen::Isometry3d::Identity();
  s.sdh_placement.linear() = r;
  if (rule == PlacementRule::kHumanPalm) {
    s.sdh_placement.translation() =
        palm * Eigen::Vector3d(kHumanGraspPoint[0], kHumanGraspPoint[1], kHumanGraspPoint[2]) -
        kSdhGraspDepth * r.col(2);
    return s;
  }
  Eigen::Vector3d centre;
  if (s.reference.kind == ReferenceCurve::Kind::kAxis) {
    const Eigen::Vector3d d = s.reference.axis.direction.normalized();
    centre = s.reference.axis.point + d * d.dot(palm_centre - s.reference.axis.point);
  } else {
    centre = s.reference.loop.leftCols(s.reference.loop.cols() - 1).rowwise().mean();
  }
  const Eigen::Isometry3d object_from_world = grasp.world_from_object.inverse();
  double depth = 0.0;  // extent of the object from the centre towards the SDH palm
  for (double t = 0.0; t < 0.3; t += 0.0005) {
    if (SignedDistance(object, object_from_world * (centre - t * r.col(2))) < 0) depth = t;
  }
  Eigen::Vector3d finger_offset = Eigen::Vector3d::Zero();
  double standoff = std::max(0.12, 0.095 + depth);
  if (s.reference.kind == ReferenceCurve::Kind::kLoop) {
    // Loops: the SDH finger with the largest target winding goes through the loop's centre, and
    // the loop sits near that finger's distal joint so the distal link can curl around it.
    const Eigen::VectorXd target =
        FingerCorrespondence() * EncodeGrasp(s.human, kin, s.human_chains, s.reference).finger;
    int f = 0;
    target.cwiseAbs().maxCoeff(&f);
    const Eigen::Vector3d bases[3] = {Eigen::Vector3d(-0.03811, 0, 0),
                                      Eigen::Vector3d(0.01905, 0.033, 0),
                                      Eigen::Vector3d(0.01905, -0.033, 0)};
    finger_offset = r * bases[f];
    standoff = 0.16;
  }
  s.sdh_placement.translation() = centre - finger_offset - standoff * r.col(2);
  return s;
}

std::vector<TransferMethod> AllTransferMethods() {
  std::vector<TransferMethod> out;
  for (const base::EnumName<TransferMethod>& e : kTransferMethodNames) out.push_back(e.value);
  return out;
}

Eigen::VectorXd PlacementConfiguration(const TransferSetup& s) {
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(s.sdh));
  q.head<3>() = s.sdh_placement.translation();
  const int spread = Dof(s.sdh, "sdh_knuckle_joint");
  q[spread] = Clamp(s.sdh, spread, s.grasp.sdh_spread);
  return q;
}

std::vector<Task> SharedTransferTasks(const TransferSetup& s, const TransferOptions& o, int T,
                                      std::vector<Task> target, bool contact) {
  const Robot& sdh = s.sdh;
  const int n = num_dofs(sdh);
  std::vector<Task> tasks;
  const HandSpheres all = SampleHandSpheres(sdh, {}, 0.006);
  std::vector<int> no_group(all.link.size(), -1);
  tasks.push_back(ConstantTask(
      "clearance",
      std::make_unique<ClearanceFeature>(all, no_group, 0, s.object, s.grasp.world_from_object,
                                         o.clearance_margin, ClearanceFeature::Mode::kHinge),
      Eigen::VectorXd::Zero(static_cast<int>(all.link.size())), o.clearance_precision, T));
  tasks.push_back(ConstantTask("joint_limits", MakeJointLimitFeature(sdh, 0.0),
                               Eigen::VectorXd::Zero(n), 1e3, T));
  tasks.push_back(FinalTask("palm", std::make_unique<PalmPoseFeature>(),
                            PlacementConfiguration(s).head<6>(), o.palm_precision, T));
  for (Task& t : target) tasks.push_back(std::move(t));
  if (contact) {
    // Contact groups: the proximal and distal link of each finger.
    std::vector<int> finger_links;
    std::vector<int> group_of_link(sdh.links.size(), -1);
    for (int f = 0; f < 3; ++f) {
      for (int li : LinksWithPrefix(sdh, kSdhFingers[f])) {
        finger_links.push_back(li);
        const std::string& name = sdh.links[li].name;
        if (name.find("proximal") != std::string::npos) group_of_link[li] = 2 * f;
        if (name.find("distal") != std::string::npos) group_of_link[li] = 2 * f + 1;
      }
    }
    const HandSpheres fs = SampleHandSpheres(sdh, finger_links, 0.006);
    std::vector<int> groups(fs.link.size());
    for (size_t k = 0; k < fs.link.size(); ++k) groups[k] = group_of_link[fs.link[k]];
    tasks.push_back(FinalTask(
        "contact",
        std::make_unique<ClearanceFeature>(fs, groups, 6, s.object, s.grasp.world_from_object, 0.0,
                                           ClearanceFeature::Mode::kMin),
        Eigen::VectorXd::Zero(6), o.contact_precision, T));
  }
  return tasks;
}

MotionProblem MakeTransferProblem(const TransferSetup& s, TransferMethod method,
                                  const TransferOptions& o) {
  if (method == TransferMethod::kHuman) {
    throw std::invalid_argument(
        "transfer method 'human' is the demonstration itself, not an SDH transfer");
  }
  const Robot& sdh = s.sdh;
  const int n = num_dofs(sdh);
  const int T = o.num_steps;
  MotionProblem problem;
  problem.robot = &sdh;
  problem.dynamic = false;
  problem.num_steps = T;
  problem.duration = 1.0;
  problem.q0 = PlacementConfiguration(s);
  problem.metric = Eigen::VectorXd::Ones(n);
  problem.metric.head<3>().setConstant(100.0);  // 1 cm of palm motion ~ 0.1 rad

  std::vector<Task> target;
  bool contact = true;
  if (method == TransferMethod::kJointMapping) {
    problem.q0 = JointMapping(s, problem.q0);
    contact = o.equal_baselines;
  } else {
    // Approach from a retracted hand.
    problem.q0.head<3>() -= o.retreat * s.sdh_placement.linear().col(2);
  }
  if (method == TransferMethod::kWinding || method == TransferMethod::kWindingOnly) {
    if (o.equal_baselines) {
      // One target rule for every object: M · y_human about the main reference only.
      const std::vector<ReferenceCurve> none;
      target.push_back(FinalTask(
          "winding", std::make_unique<GraspWindingFeature>(s.sdh_chains, s.reference, none, true),
          WindingTarget(s, true), o.winding_precision, T));
    } else {
      target.push_back(FinalTask(
          "winding",
          std::make_unique<GraspWindingFeature>(s.sdh_chains, s.reference, s.extra_references,
                                                s.object.main_reference_in_target),
          WindingTarget(s), o.winding_precision, T));
    }
    contact = method == TransferMethod::kWinding;
  } else if (method == TransferMethod::kFingertip) {
    // Fingertip mapping: SDH tips to the human tips of the corresponding fingers.
    KinematicsData hkin(s.human);
    ForwardKinematics(s.human, s.human_q, &hkin);
    const std::vector<std::vector<std::string>> human_tips = {
        {"thumb"}, {"ring", "little"}, {"index", "middle"}};
    for (int f = 0; f < 3; ++f) {
      Eigen::Vector3d tip = Eigen::Vector3d::Zero();
      for (const std::string& h : human_tips[f]) {
        Eigen::Matrix3Xd pts;
        ChainPoints(s.human, hkin, FindChain(s.human, "grasp_" + h), &pts);
        tip += pts.col(pts.cols() - 1) / static_cast<double>(human_tips[f].size());
      }
      const int distal = FindLink(sdh, std::string(kSdhFingers[f]) + "_distal");
      target.push_back(FinalTask(std::string("tip_") + kSdhFingers[f],
                                 MakePositionFeature(sdh, distal, Eigen::Vector3d(0, 0, 0.0685)),
                                 tip, o.tip_precision, T));
    }
  }
  problem.tasks = SharedTransferTasks(s, o, T, std::move(target), contact);
  return problem;
}

TransferResult TransferGrasp(const TransferSetup& s, TransferMethod method,
                             const TransferOptions& o) {
  const Robot& sdh = s.sdh;
  TransferResult res;
  res.method = method;
  MotionProblem problem = MakeTransferProblem(s, method, o);
  const int T = problem.num_steps;

  // Human encoding and the mapped target.
  KinematicsData hkin(s.human);
  ForwardKinematics(s.human, s.human_q, &hkin);
  const GraspEncoding human_enc = EncodeGrasp(s.human, hkin, s.human_chains, s.reference);
  res.human_winding = human_enc.finger;
  res.human_phalanx_winding = human_enc.phalanx;
  res.target_winding = FingerCorrespondence() * res.human_winding;

  // Multi-start (deterministic): one AICO run per initial flexion, keep the lowest cost. The
  // joint method runs once from its mapped posture.
  AicoWorkspace ws(problem);
  const Eigen::VectorXd q0 = problem.q0;
  const bool mapped = method == TransferMethod::kJointMapping;
  const std::vector<double> flexions =
      mapped && !o.equal_baselines ? std::vector<double>{0.0} : o.initial_flexions;
  double best_cost = std::numeric_limits<double>::infinity();
  for (double flex : flexions) {
    problem.q0 = q0;
    for (int f = 0; f < 3; ++f) {
      for (const char* joint : {"_proximal_joint", "_distal_joint"}) {
        const int k = Dof(sdh, std::string(kSdhFingers[f]) + joint);
        // Joint mapping: the start is offset from the mapped posture; the others start at flex.
        problem.q0[k] = mapped ? Clamp(sdh, k, q0[k] + flex) : flex;
      }
    }
    const AicoResult r = SolveAico(problem, o.aico, &ws);
    ++res.starts;
    res.task_evaluations += r.task_evaluations;
    if (r.cost < best_cost) {
      best_cost = r.cost;
      res.trajectory = r.trajectory;
      res.q = r.trajectory.q.col(T);
      res.status = r.status;
      res.iterations = r.iterations;
    }
  }
  res.solver = "aico";

  // Encoding and clearance of the result.
  KinematicsData kin(sdh);
  ForwardKinematics(sdh, res.q, &kin);
  const GraspEncoding enc = EncodeGrasp(sdh, kin, s.sdh_chains, s.reference);
  res.robot_winding = enc.finger;
  res.robot_phalanx_winding = enc.phalanx;
  if (!s.extra_references.empty()) {
    res.target_extra_winding = WindingTarget(s).tail(2 * s.extra_references.size());
    res.robot_extra_winding.resize(2 * s.extra_references.size());
    for (size_t r = 0; r < s.extra_references.size(); ++r) {
      res.robot_extra_winding.segment<2>(2 * r) =
          OppositionPair(EncodeGrasp(sdh, kin, s.sdh_chains, s.extra_references[r]).finger);
    }
  }
  res.min_clearance = HandClearance(sdh, kin, SampleHandSpheres(sdh, {}, 0.003), s.object,
                                    s.grasp.world_from_object);
  return res;
}

}  // namespace planning
