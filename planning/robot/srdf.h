// SRDF (the semantic robot description of MoveIt) for a robot loaded from URDF: which link pairs
// are never collision-checked and named configurations.
//
// Read:
//   <disable_collisions link1="A" link2="B" reason=".."/>  the pair (A, B) is never checked
//                                                          (CollisionOptions::disabled_pairs);
//   <group_state name="ready" group="arm">                 a named configuration: each <joint
//     <joint name="j1" value="0.3"/> ...                   name= value=> sets that joint of q;
//   </group_state>                                         joints it does not name stay 0;
//   <passive_joint name="j"/>                              listed (Srdf::passive_joints) only: the
//                                                          joint stays in q like any other;
//   <virtual_joint name= type= parent_frame= child_link=>  type floating or planar on the root
//                                                          link: the robot has a free base
//                                                          (ApplySrdfBase); a group_state value
//                                                          for it is the base pose
//                                                          (NamedBasePose), not part of q.
// Pinocchio's convention is understood too: group_states giving 7 values to a joint 'root_joint'
// that neither the URDF nor a virtual_joint declares make the root a floating base.
// <group> is read (Srdf::groups; GroupDofs, e.g. a scenario's "frozen_joints": ["gripper"]).
// <end_effector name= parent_link= group=> is read (Srdf::end_effectors; `scenario new` takes its
// hand from one when the robot's tree branches before a serial arm).
// Ignored: <disable_default_collisions>, <enable_collisions>,
// <link_sphere_approximations> and any other element.
//
// Errors (std::invalid_argument, "FILE:LINE: ..."): unreadable file, XML errors, XML nested
// deeper than 100 elements, a root other than <robot> or more than one top-level element or text
// after it, a <disable_collisions> without link1/link2, a <group_state> without a name or with a
// duplicate name, a <joint> without name or whose value is not a finite number. Against a robot:
// a value with more numbers than its joint has variables is an error (NamedPose); names the robot
// does not have and an SRDF written for another robot name are warnings (CheckSrdf): the
// entries are skipped, as MoveIt skips them, and `--strict` turns the warnings into errors.
//
// Where an SRDF comes from when none is given (FindSrdf): NAME.srdf next to NAME.urdf, else
// ../srdf/NAME.srdf (the sibling srdf/ folder of the URDF's folder).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "planning/robot/robot.h"

namespace planning {

struct SrdfPair {
  std::string link1, link2;
  int line = 0;
};

struct SrdfJointValue {
  std::string joint;
  std::vector<double> values;  // rad or m; one per variable of the joint (several: multi-DOF)
  int line = 0;
};

struct SrdfPose {  // a <group_state>
  std::string name, group;
  std::vector<SrdfJointValue> joints;
  int line = 0;
};

struct SrdfGroup {  // a <group>: its <joint>, <link>, <chain> and <group> children by name
  std::string name;
  std::vector<std::string> joints, links, subgroups;
  std::vector<std::pair<std::string, std::string>> chains;  // (base_link, tip_link)
  int line = 0;
};

struct SrdfVirtualJoint {
  std::string name, type, parent_frame, child_link;  // type: fixed, floating or planar
  int line = 0;
};

struct SrdfEndEffector {  // an <end_effector>: the link it hangs from and its group
  std::string name, parent_link, group;
  int line = 0;
};

struct Srdf {
  std::string source;      // file name for messages
  std::string robot_name;  // <robot name=>
  std::vector<SrdfPair> disabled_pairs;
  std::vector<SrdfPose> poses;
  std::vector<std::string> passive_joints;  // read, not used (see the file comment)
  std::vector<SrdfVirtualJoint> virtual_joints;
  std::vector<SrdfGroup> groups;
  std::vector<SrdfEndEffector> end_effectors;  // in file order
};

// Parses SRDF text; `source` names it in messages.
Srdf ParseSrdf(const std::string& xml, const std::string& source);

// Reads and parses an SRDF file.
Srdf LoadSrdf(const std::string& path);

// The warnings of `srdf` against `robot` ("FILE:LINE: ..."): an SRDF <robot name=> other than the
// URDF's; every link of a disabled pair and every group_state joint (other than virtual joints)
// that `robot` does not have (such entries are skipped by DisabledPairs and NamedPose). Empty when
// the SRDF fits the robot.
std::vector<std::string> CheckSrdf(const Srdf& srdf, const Robot& robot);

// The disabled pairs as (link1, link2) names, for CollisionOptions::disabled_pairs; pairs that name
// links the robot does not have are left out when `robot` is given.
std::vector<std::pair<std::string, std::string>> DisabledPairs(const Srdf& srdf,
                                                               const Robot* robot = nullptr);

// Configuration q (size num_dofs) of the group_state `name`: zeros, with each named independent
// joint set to its value (mimic and fixed joints are skipped: they follow q; joints the robot does
// not have are skipped, CheckSrdf warns of them). Throws std::invalid_argument listing the
// available names when there is no such pose, and naming the joint and line when a value has
// more numbers than the joint has variables. A value outside the joint's limits: with `warnings`
// given, kept and described there (the caller asked about that pose: `check`, `fk`, `render`);
// without, an error naming the joint and its limits (a start for planning).
Eigen::VectorXd NamedPose(const Robot& robot, const Srdf& srdf, const std::string& name,
                          std::vector<std::string>* warnings = nullptr);

// Makes `robot` a free-base robot when the SRDF says so: a floating or planar virtual_joint whose
// child_link is the root link, else group_states giving 7 values to an undeclared 'root_joint'
// (Pinocchio's free-flyer). Sets robot->base_type and base_joint; a URDF free base is kept.
// Returns warnings (a virtual_joint that conflicts with the URDF's free base).
std::vector<std::string> ApplySrdfBase(const Srdf& srdf, Robot* robot);

// The base pose (world_from_root) the group_state `name` gives the free base: nullopt when the
// robot has no free base or the pose does not name it. Throws std::invalid_argument as NamedPose
// for an unknown pose, and for values that are not a pose (BasePoseFromValues).
std::optional<Eigen::Isometry3d> NamedBasePose(const Robot& robot, const Srdf& srdf,
                                               const std::string& name);

// A base pose from numbers: x,y,z (3) or x,y,z,qx,qy,qz,qw (7, the quaternion normalised; the
// order of Pinocchio and MoveIt), or for a planar base x,y,theta (3: a turn theta [rad] about
// the world z axis). Throws std::invalid_argument starting with `where` for another count, a
// value that is not finite or a zero quaternion.
Eigen::Isometry3d BasePoseFromValues(BaseType type, const std::vector<double>& values,
                                     const std::string& where);

// The dofs (indices into q, sorted) a <group> moves: its joints, the joints whose child is one of
// its links, the joints of its chains (tip up to base) and of its subgroups; fixed joints add
// nothing, a mimic joint its master. Throws std::invalid_argument "<source>[:<line>]: ..." for an
// unknown group (listing the groups), a chain whose base is not above its tip, or subgroups
// nested in a cycle; names the robot lacks are skipped (CheckSrdf warns of them).
std::vector<int> GroupDofs(const Robot& robot, const Srdf& srdf, const std::string& group);

// The SRDF of the URDF at `urdf_path` (NAME.urdf) whose <robot name> is `robot_name`, looked for
// in the URDF's folder, then in the sibling ../srdf/: NAME.srdf, else ROBOT_NAME.srdf, else the
// first (by file name) *.srdf there whose <robot name> is robot_name; "" when there is none.
std::string FindSrdf(const std::string& urdf_path, const std::string& robot_name = "");

}  // namespace planning
