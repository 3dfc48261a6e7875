#include "planning/physics/grasp_trial_codec.h"

#include <cstdint>

#include "base/byte_codec.h"

namespace planning::physics {
namespace {

constexpr std::uint32_t kMagic = 0x31544754;  // "TGT1"

using Writer = base::ByteWriter;
using Reader = base::ByteReader;

void PutTransfer(const TransferResult& t, Writer* w) {
  w->Pod(t.method);
  w->Vector(t.q);
  w->Matrix(t.trajectory.q);
  w->Pod(t.trajectory.dt);
  w->Vector(t.human_winding);
  w->Vectors(t.human_phalanx_winding);
  w->Vector(t.target_winding);
  w->Vector(t.robot_winding);
  w->Vectors(t.robot_phalanx_winding);
  w->Vector(t.target_extra_winding);
  w->Vector(t.robot_extra_winding);
  w->Pod(t.min_clearance);
  w->String(t.solver);
  w->Pod(t.status);
  w->Pod(t.iterations);
  w->Pod(t.starts);
  w->Pod(t.task_evaluations);
}

TransferResult GetTransfer(Reader* r) {
  TransferResult t;
  t.method = r->Pod<TransferMethod>();
  t.q = r->Vector();
  t.trajectory.q = r->Matrix();
  t.trajectory.dt = r->Pod<double>();
  t.human_winding = r->Vector();
  t.human_phalanx_winding = r->Vectors();
  t.target_winding = r->Vector();
  t.robot_winding = r->Vector();
  t.robot_phalanx_winding = r->Vectors();
  t.target_extra_winding = r->Vector();
  t.robot_extra_winding = r->Vector();
  t.min_clearance = r->Pod<double>();
  t.solver = r->String();
  t.status = r->Pod<SolveStatus>();
  t.iterations = r->Pod<int>();
  t.starts = r->Pod<int>();
  t.task_evaluations = r->Pod<long>();
  return t;
}

void PutStability(const StabilityResult& s, Writer* w) {
  w->Pod(s.status);
  w->Size(s.directions.size());
  for (const DirectionResult& d : s.directions) {
    w->String(d.label);
    w->Vec3(d.gravity_palm);
    w->Pod(d.passed);
    w->Pod(d.slip_m);
    w->Pod(d.rotation_deg);
    w->Pod(d.contact_links);
    w->Pod(d.blown_up);
    w->String(d.blowup_reason);
    w->Pod(d.steps);
  }
  w->Pod(s.directions_passed);
  w->Pod(s.stable);
  w->Pod(s.max_slip_m);
  w->Pod(s.max_rotation_deg);
  w->Pod(s.closure_contact_links);
  w->Pod(s.closure_max_depth);
  w->Size(s.closure_contacts.size());
  for (const SimContact& c : s.closure_contacts) {
    w->Vec3(c.position);
    w->Vec3(c.normal);
    w->Pod(c.depth);
    w->Pod(c.link);
  }
  w->Pose(s.closure_world_from_object);
  w->String(s.message);
  w->Pod(s.total_steps);
}

StabilityResult GetStability(Reader* r) {
  StabilityResult s;
  s.status = r->Pod<StabilityStatus>();
  s.directions.resize(r->Size());
  for (DirectionResult& d : s.directions) {
    d.label = r->String();
    d.gravity_palm = r->Vec3();
    d.passed = r->Pod<bool>();
    d.slip_m = r->Pod<double>();
    d.rotation_deg = r->Pod<double>();
    d.contact_links = r->Pod<int>();
    d.blown_up = r->Pod<bool>();
    d.blowup_reason = r->String();
    d.steps = r->Pod<int>();
  }
  s.directions_passed = r->Pod<int>();
  s.stable = r->Pod<bool>();
  s.max_slip_m = r->Pod<double>();
  s.max_rotation_deg = r->Pod<double>();
  s.closure_contact_links = r->Pod<int>();
  s.closure_max_depth = r->Pod<double>();
  s.closure_contacts.resize(r->Size());
  for (SimContact& c : s.closure_contacts) {
    c.position = r->Vec3();
    c.normal = r->Vec3();
    c.depth = r->Pod<double>();
    c.link = r->Pod<int>();
  }
  s.closure_world_from_object = r->Pose();
  s.message = r->String();
  s.total_steps = r->Pod<long>();
  return s;
}

}  // namespace

std::string EncodeGraspTrial(const GraspTrial& trial) {
  Writer w;
  w.Pod(kMagic);
  PutTransfer(trial.transfer, &w);
  PutStability(trial.stability, &w);
  w.Pod(trial.winding_error);
  w.Pod(trial.epsilon_quality);
  w.Pod(trial.human);
  w.Size(trial.perturbed.size());
  for (const PerturbedTrial& p : trial.perturbed) {
    w.Pose(p.world_from_object);
    w.Pod(p.stable);
    w.Pod(p.directions_passed);
    w.Pod(p.epsilon_quality);
  }
  w.Pod(trial.perturbed_stable);
  w.Pod(kMagic);
  return w.Take();
}

GraspTrial DecodeGraspTrial(const std::string& bytes) {
  Reader r(bytes, "grasp trial");
  auto magic = [&r] {
    if (r.Pod<std::uint32_t>() != kMagic) r.Fail();
  };
  magic();
  GraspTrial trial;
  trial.transfer = GetTransfer(&r);
  trial.stability = GetStability(&r);
  trial.winding_error = r.Pod<double>();
  trial.epsilon_quality = r.Pod<double>();
  trial.human = r.Pod<bool>();
  trial.perturbed.resize(r.Size());
  for (PerturbedTrial& p : trial.perturbed) {
    p.world_from_object = r.Pose();
    p.stable = r.Pod<bool>();
    p.directions_passed = r.Pod<int>();
    p.epsilon_quality = r.Pod<double>();
  }
  trial.perturbed_stable = r.Pod<int>();
  magic();
  if (!r.at_end()) r.Fail();
  return trial;
}

}  // namespace planning::physics
