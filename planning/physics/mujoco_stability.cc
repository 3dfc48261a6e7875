// The stability protocol in MuJoCo 2.2 (planning/physics/mujoco_stability.h). Compiled only with
// TOPOPLAN_WITH_MUJOCO; the MJCF comes from MujocoModelXml (mujoco_model.cc).
#include "planning/physics/mujoco_stability.h"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace planning::physics {
namespace {

struct ModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct DataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};
struct VfsDeleter {
  void operator()(mjVFS* v) const {
    mj_deleteVFS(v);
    delete v;
  }
};

// Loads MJCF text through MuJoCo's virtual file system (mj_loadXML takes a file name).
std::unique_ptr<mjModel, ModelDeleter> LoadModel(const std::string& xml) {
  std::unique_ptr<mjVFS, VfsDeleter> vfs(new mjVFS);
  mj_defaultVFS(vfs.get());
  const char* name = "grasp.xml";
  if (mj_makeEmptyFileVFS(vfs.get(), name, static_cast<int>(xml.size())) != 0) {
    throw std::runtime_error("MuJoCo: cannot create the in-memory model file");
  }
  const int index = mj_findFileVFS(vfs.get(), name);
  std::memcpy(vfs->filedata[index], xml.data(), xml.size());
  char error[1000] = "";
  mjModel* m = mj_loadXML(name, vfs.get(), error, sizeof(error));
  if (!m) throw std::runtime_error(std::string("MuJoCo rejected the grasp model: ") + error);
  return std::unique_ptr<mjModel, ModelDeleter>(m);
}

// The running simulation with the indices the protocol reads.
struct Sim {
  std::unique_ptr<mjModel, ModelDeleter> model;
  std::unique_ptr<mjData, DataDeleter> data;
  int object_body = -1;
  std::vector<int> link_of_body;  // hand link index per MuJoCo body, −1 otherwise
  std::vector<int> qpos_adr;      // per hand link (0 for the palm)
  std::vector<double> q_start, q_target;
  Eigen::Isometry3d world_from_palm = Eigen::Isometry3d::Identity();
};

Eigen::Isometry3d ObjectPose(const Sim& s) {
  const mjData* d = s.data.get();
  const int b = s.object_body;
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = Eigen::Vector3d(d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2]);
  p.linear() = Eigen::Quaterniond(d->xquat[4 * b], d->xquat[4 * b + 1], d->xquat[4 * b + 2],
                                  d->xquat[4 * b + 3])
                   .toRotationMatrix();
  return p;
}

// Hand–object contacts of the current step (normals from the object towards the hand) and the
// number of distinct hand links among them.
int Contacts(const Sim& s, std::vector<SimContact>* out) {
  const mjModel* m = s.model.get();
  const mjData* d = s.data.get();
  std::vector<char> touched(s.qpos_adr.size(), 0);
  if (out) out->clear();
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    const int b1 = m->geom_bodyid[c.geom1], b2 = m->geom_bodyid[c.geom2];
    const bool object_first = b1 == s.object_body;
    const int link = s.link_of_body[object_first ? b2 : b1];
    if (link < 0 || (!object_first && b2 != s.object_body)) continue;
    touched[link] = 1;
    if (out) {
      SimContact sc;
      sc.position = Eigen::Vector3d(c.pos[0], c.pos[1], c.pos[2]);
      const Eigen::Vector3d n(c.frame[0], c.frame[1], c.frame[2]);  // geom1 → geom2
      sc.normal = object_first ? n : -n;
      sc.depth = std::max(0.0, -c.dist);
      sc.link = link;
      out->push_back(sc);
    }
  }
  return static_cast<int>(std::count(touched.begin(), touched.end(), 1));
}

// Velocity set-points as ODE's motor loop, then one mj_step; false once the state blew up.
bool Step(Sim* s, const SimOptions& o, std::string* reason) {
  mjData* d = s->data.get();
  for (size_t i = 1; i < s->qpos_adr.size(); ++i) {
    const double q = s->q_start[i] + d->qpos[s->qpos_adr[i]];
    d->ctrl[i - 1] =
        std::clamp(o.motor_gain * (s->q_target[i] - q), -o.max_joint_speed, o.max_joint_speed);
  }
  mj_step(s->model.get(), d);
  const mjModel* m = s->model.get();
  bool finite = true;
  for (int i = 0; i < m->nq; ++i) finite = finite && std::isfinite(d->qpos[i]);
  const int f = m->jnt_dofadr[m->body_jntadr[s->object_body]];
  const Eigen::Vector3d v(d->qvel[f], d->qvel[f + 1], d->qvel[f + 2]);
  const Eigen::Vector3d w(d->qvel[f + 3], d->qvel[f + 4], d->qvel[f + 5]);
  if (!finite) {
    *reason = "non-finite state";
  } else if (d->warning[mjWARN_BADQACC].number > 0) {
    *reason = "MuJoCo: bad acceleration";
  } else if (v.norm() > o.blowup_linear_speed) {
    *reason = "object faster than " + std::to_string(o.blowup_linear_speed) + " m/s";
  } else if (w.norm() > o.blowup_angular_speed) {
    *reason = "object spins faster than " + std::to_string(o.blowup_angular_speed) + " rad/s";
  } else {
    return true;
  }
  return false;
}

// The state as GraspSimulation::state() reports it (for a StateCallback).
SimState State(const Sim& s, int step) {
  const mjData* d = s.data.get();
  SimState st;
  st.time = d->time;
  st.step = step;
  for (size_t b = 0; b < s.link_of_body.size(); ++b) {
    const int link = s.link_of_body[b];
    if (link < 0) continue;
    if (st.world_from_link.size() <= static_cast<size_t>(link)) {
      st.world_from_link.resize(link + 1);
      st.joint_angles.resize(link + 1, 0.0);
    }
    Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
    p.translation() = Eigen::Vector3d(d->xpos[3 * b], d->xpos[3 * b + 1], d->xpos[3 * b + 2]);
    p.linear() = Eigen::Quaterniond(d->xquat[4 * b], d->xquat[4 * b + 1], d->xquat[4 * b + 2],
                                    d->xquat[4 * b + 3])
                     .toRotationMatrix();
    st.world_from_link[link] = p;
    if (link > 0) st.joint_angles[link] = s.q_start[link] + d->qpos[s.qpos_adr[link]];
  }
  st.world_from_object = ObjectPose(s);
  st.num_contact_links = Contacts(s, &st.contacts);
  for (const SimContact& c : st.contacts) st.max_depth = std::max(st.max_depth, c.depth);
  return st;
}

}  // namespace

StabilityResult TestGraspStabilityMujoco(const SimHand& hand, const SimObject& object,
                                         const StabilityOptions& options,
                                         const MujocoOptions& mujoco,
                                         const StateCallback& on_state) {
  if (!(options.close_time >= 0) || !(options.trial_time > 0) || !(options.max_slip > 0) ||
      !(options.max_rotation_deg > 0) || !std::isfinite(options.gravity)) {
    throw std::invalid_argument(
        "stability options: need close_time >= 0, trial_time > 0, max_slip > 0, "
        "max_rotation_deg > 0 and finite gravity");
  }
  const SimOptions& o = options.sim;
  Sim s;
  s.model = LoadModel(MujocoModelXml(hand, object, o, mujoco));
  mjModel* m = s.model.get();
  s.data.reset(mj_makeData(m));
  const int n = static_cast<int>(hand.links.size());
  s.object_body = mj_name2id(m, mjOBJ_BODY, "object");
  s.link_of_body.assign(m->nbody, -1);
  s.qpos_adr.assign(n, 0);
  for (int i = 0; i < n; ++i) {
    const std::string body = "link" + std::to_string(i);
    s.link_of_body[mj_name2id(m, mjOBJ_BODY, body.c_str())] = i;
    s.q_start.push_back(hand.links[i].q_start);
    s.q_target.push_back(hand.links[i].q_target);
    if (i > 0) {
      const std::string joint = "j" + std::to_string(i);
      s.qpos_adr[i] = m->jnt_qposadr[mj_name2id(m, mjOBJ_JOINT, joint.c_str())];
    }
  }
  s.world_from_palm = hand.links[0].world_from_link;
  mj_forward(m, s.data.get());

  StabilityResult result;
  static const char* kLabels[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
  result.directions.resize(6);
  for (int k = 0; k < 6; ++k) {
    result.directions[k].label = kLabels[k];
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    g[k / 2] = (k % 2 == 0 ? 1.0 : -1.0) * options.gravity;
    result.directions[k].gravity_palm = g;
  }
  const int close_steps = static_cast<int>(std::lround(options.close_time / o.dt));
  const int trial_steps = static_cast<int>(std::lround(options.trial_time / o.dt));
  std::string reason;
  bool ok = true;
  for (int k = 0; k < close_steps && ok; ++k) {
    ok = Step(&s, o, &reason);
    ++result.total_steps;
    if (on_state) on_state(0, State(s, k + 1));
  }
  result.closure_contact_links = Contacts(s, &result.closure_contacts);
  for (const SimContact& c : result.closure_contacts) {
    result.closure_max_depth = std::max(result.closure_max_depth, c.depth);
  }
  result.closure_world_from_object = ObjectPose(s);
  if (!ok) {
    result.status = StabilityStatus::kBlownUp;
    result.message = "closing phase: " + reason;
    for (DirectionResult& d : result.directions) {
      d.blown_up = true;
      d.blowup_reason = result.message;
    }
    return result;
  }
  if (result.closure_contact_links < options.min_contact_links) {
    result.status = StabilityStatus::kNoGrasp;
    result.message = "after closing only " + std::to_string(result.closure_contact_links) +
                     " hand link(s) touch the object";
    return result;
  }
  // Post-closure state; every gravity direction starts from it.
  mjData* d = s.data.get();
  const std::vector<double> qpos(d->qpos, d->qpos + m->nq), qvel(d->qvel, d->qvel + m->nv),
      warm(d->qacc_warmstart, d->qacc_warmstart + m->nv);
  const double time = d->time;
  const Eigen::Isometry3d reference = s.world_from_palm.inverse() * ObjectPose(s);
  bool any_blowup = false;
  for (int k = 0; k < 6; ++k) {
    DirectionResult& dir = result.directions[k];
    std::copy(qpos.begin(), qpos.end(), d->qpos);
    std::copy(qvel.begin(), qvel.end(), d->qvel);
    std::copy(warm.begin(), warm.end(), d->qacc_warmstart);
    d->time = time;
    const Eigen::Vector3d g = s.world_from_palm.linear() * dir.gravity_palm;
    for (int i = 0; i < 3; ++i) m->opt.gravity[i] = g[i];
    mj_forward(m, d);
    ok = true;
    double slip = 0, rot = 0;
    while (dir.steps < trial_steps) {
      ok = Step(&s, o, &reason);
      ++dir.steps;
      if (on_state) on_state(k + 1, State(s, close_steps + dir.steps));
      if (!ok) break;
      PoseDrift(reference, s.world_from_palm.inverse() * ObjectPose(s), &slip, &rot);
      if (slip > options.early_exit_slip) break;
    }
    result.total_steps += dir.steps;
    if (!ok) {
      dir.blown_up = true;
      dir.blowup_reason = reason;
      any_blowup = true;
      if (result.message.empty()) result.message = "gravity " + dir.label + ": " + reason;
      continue;
    }
    PoseDrift(reference, s.world_from_palm.inverse() * ObjectPose(s), &dir.slip_m,
              &dir.rotation_deg);
    mj_forward(m, d);  // contacts of the final state
    dir.contact_links = Contacts(s, nullptr);
    dir.passed = dir.slip_m < options.max_slip && dir.rotation_deg < options.max_rotation_deg &&
                 dir.contact_links >= options.min_contact_links;
    result.directions_passed += dir.passed ? 1 : 0;
    result.max_slip_m = std::max(result.max_slip_m, dir.slip_m);
    result.max_rotation_deg = std::max(result.max_rotation_deg, dir.rotation_deg);
  }
  if (any_blowup) result.status = StabilityStatus::kBlownUp;
  result.stable = result.status == StabilityStatus::kTested && result.directions_passed == 6;
  return result;
}

}  // namespace planning::physics
