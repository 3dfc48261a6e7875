// The grasp stability protocol (stability.h) in a second physics engine, MuJoCo 2.2 (Todorov,
// Erez & Tassa 2012; Debian's libmujoco-dev), behind one interface with ODE: the same plain-data
// hand and object (SimHand, SimObject), the same phases (closing with gravity off, then gravity
// along the six palm axes from the post-closure state) and the same pass criteria
// (StabilityOptions: slip, rotation, contact links). MuJoCo is optional at build time
// (TOPOPLAN_WITH_MUJOCO); ODE stays the default engine.
#pragma once

#include <functional>
#include <span>
#include <string>

#include "base/enum_names.h"
#include "planning/physics/grasp_simulation.h"
#include "planning/physics/ode_runtime.h"
#include "planning/physics/stability.h"

namespace planning::physics {

enum class PhysicsEngine { kOde, kMujoco };
inline constexpr base::EnumName<PhysicsEngine> kPhysicsEngineNames[] = {
    {PhysicsEngine::kOde, "ode"},
    {PhysicsEngine::kMujoco, "mujoco"},
};
constexpr std::span<const base::EnumName<PhysicsEngine>> EnumNames(PhysicsEngine) {
  return kPhysicsEngineNames;
}
inline const char* ToString(PhysicsEngine engine) { return base::ToName(engine); }

// Whether this build can run `engine` (ODE always; MuJoCo when libmujoco-dev was found).
bool EngineAvailable(PhysicsEngine engine);

// How the description maps to MuJoCo (MJCF written in memory, loaded through MuJoCo's virtual
// file system). Per hand joint: a hinge (range = the SimHandLink limits) driven by a velocity
// actuator with gain kv = kv_per_torque · max_torque [N m s/rad], force limited to ±max_torque,
// whose set-point each step is clamp(motor_gain (q_target − q), ±max_joint_speed) as in ODE
// (SimOptions); the implicit-in-velocity integrator (mjINT_IMPLICIT) keeps the stiff velocity
// loop stable at SimOptions::dt. Contacts only between hand and object; a pyramidal friction cone
// with SimOptions::mu, and with a soft-finger patch (contact_patch_radius > 0) condim 4 with the
// torsional coefficient SoftFingerSpinArm(mu, a) [m]; contact softness solref = (contact_time_
// constant, 1), MuJoCo's default solimp. Masses spread over the shapes by volume as in ODE.
struct MujocoOptions {
  double kv_per_torque = 10.0;           // [s/rad]: saturates at 0.1 rad/s of velocity error
  double contact_time_constant = 0.005;  // solref[0] [s] (MuJoCo needs >= 2 dt)
  double armature = 1e-5;                // rotor inertia added to every hinge [kg m²]
};

// TestGraspStability in MuJoCo: the same phases and verdicts (StabilityResult) as the ODE run;
// closure_contacts hold MuJoCo's hand–object contacts after closing (normals from the object
// towards the hand). A closing that leaves fewer than min_contact_links links touching gives
// kNoGrasp without simulating the gravity directions (ODE simulates them; the verdict, not
// stable, is the same). Only the motorised hand (HandMode::kMotorized) and primitive shapes (no
// kTrimesh). Deterministic. Throws std::invalid_argument for a description GraspSimulation
// rejects, a trimesh or a kinematic hand, std::runtime_error when MuJoCo rejects the model or
// the build has no MuJoCo.
// `on_state` (optional) sees the state after every step as ODE's StepCallback sees
// GraspSimulation::state(): phase 0 closing, 1..6 the gravity directions; `step` counts from the
// start of closing along the phase's branch; contacts are the hand–object ones.
using StateCallback = std::function<void(int phase, const SimState& state)>;
StabilityResult TestGraspStabilityMujoco(const SimHand& hand, const SimObject& object,
                                         const StabilityOptions& options,
                                         const MujocoOptions& mujoco = {},
                                         const StateCallback& on_state = {});

// The MJCF text TestGraspStabilityMujoco loads (for inspection and tests); available in every
// build. Same argument checks.
std::string MujocoModelXml(const SimHand& hand, const SimObject& object, const SimOptions& sim,
                           const MujocoOptions& mujoco = {});

// The protocol in `engine`: TestGraspStability (ODE, `runtime`) or TestGraspStabilityMujoco
// (default MujocoOptions). Throws std::runtime_error for an engine this build lacks.
StabilityResult TestGraspStabilityIn(PhysicsEngine engine, const OdeRuntime& runtime,
                                     const SimHand& hand, const SimObject& object,
                                     const StabilityOptions& options);

}  // namespace planning::physics
