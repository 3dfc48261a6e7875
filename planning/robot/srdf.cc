// SRDF reading (planning/robot/srdf.h): TinyXML after the depth pre-scan.
#include "planning/robot/srdf.h"

#include <tinyxml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "base/file_read.h"
#include "base/numbers.h"
#include "planning/robot/internal/xml_text.h"

namespace planning {
namespace {

namespace fs = std::filesystem;
using internal::FailAt;
using internal::XmlAttr;

}  // namespace

Srdf ParseSrdf(const std::string& xml, const std::string& source) {
  internal::CheckXmlUtf8(xml, source);
  internal::CheckXmlDepth(xml, source);
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  if (doc.Error()) FailAt(source, doc.ErrorRow(), std::string("XML error: ") + doc.ErrorDesc());
  const TiXmlElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Value()) != "robot") {
    FailAt(source, robot ? robot->Row() : 0, "the root element of an SRDF must be <robot>");
  }
  internal::CheckSingleRoot(doc, source);
  internal::CheckNoTrailingText(xml, source);
  Srdf s;
  s.source = source;
  s.robot_name = XmlAttr(robot, "name");
  std::set<std::string> pose_names;
  for (const TiXmlElement* e = robot->FirstChildElement(); e; e = e->NextSiblingElement()) {
    const std::string tag = e->Value();
    if (tag == "disable_collisions") {
      SrdfPair p{XmlAttr(e, "link1"), XmlAttr(e, "link2"), e->Row()};
      if (p.link1.empty() || p.link2.empty()) {
        FailAt(source, e->Row(), "<disable_collisions> needs link1= and link2=");
      }
      s.disabled_pairs.push_back(p);
    } else if (tag == "group_state") {
      SrdfPose pose{XmlAttr(e, "name"), XmlAttr(e, "group"), {}, e->Row()};
      if (pose.name.empty()) FailAt(source, e->Row(), "<group_state> without a name");
      if (!pose_names.insert(pose.name).second) {
        FailAt(source, e->Row(), "duplicate group_state '" + pose.name + "'");
      }
      for (const TiXmlElement* j = e->FirstChildElement("joint"); j;
           j = j->NextSiblingElement("joint")) {
        SrdfJointValue v{XmlAttr(j, "name"), {}, j->Row()};
        if (v.joint.empty())
          FailAt(source, j->Row(), "group_state '" + pose.name + "': <joint> without a name");
        std::vector<double> numbers;
        if (!internal::ParseNumbers(XmlAttr(j, "value"), 0, &numbers)) {
          FailAt(source, j->Row(),
                 "group_state '" + pose.name + "' joint '" + v.joint +
                     "': value= must be finite numbers, got '" + XmlAttr(j, "value") + "'");
        }
        v.values = numbers;  // the arity is checked against the joint (NamedPose)
        pose.joints.push_back(v);
      }
      s.poses.push_back(pose);
    } else if (tag == "group") {
      SrdfGroup g;
      g.name = XmlAttr(e, "name");
      g.line = e->Row();
      if (g.name.empty()) FailAt(source, e->Row(), "<group> without a name");
      for (const TiXmlElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
        const std::string ctag = c->Value();
        if (ctag == "joint") g.joints.push_back(XmlAttr(c, "name"));
        if (ctag == "link") g.links.push_back(XmlAttr(c, "name"));
        if (ctag == "group") g.subgroups.push_back(XmlAttr(c, "name"));
        if (ctag == "chain") g.chains.emplace_back(XmlAttr(c, "base_link"), XmlAttr(c, "tip_link"));
      }
      s.groups.push_back(std::move(g));
    } else if (tag == "passive_joint") {
      s.passive_joints.push_back(XmlAttr(e, "name"));
    } else if (tag == "virtual_joint") {
      SrdfVirtualJoint v{XmlAttr(e, "name"), XmlAttr(e, "type"), XmlAttr(e, "parent_frame"),
                         XmlAttr(e, "child_link"), e->Row()};
      if (v.name.empty()) FailAt(source, e->Row(), "<virtual_joint> without a name");
      if (v.type != "fixed" && v.type != "floating" && v.type != "planar") {
        FailAt(source, e->Row(),
               "virtual_joint '" + v.name + "': type '" + v.type +
                   "' (expected fixed, floating or planar)");
      }
      s.virtual_joints.push_back(v);
    } else if (tag == "end_effector") {
      SrdfEndEffector ee{XmlAttr(e, "name"), XmlAttr(e, "parent_link"), XmlAttr(e, "group"),
                         e->Row()};
      if (ee.parent_link.empty()) FailAt(source, e->Row(), "<end_effector> without a parent_link");
      s.end_effectors.push_back(ee);
    }
  }
  return s;
}

Srdf LoadSrdf(const std::string& path) {
  return ParseSrdf(base::ReadFileBounded(path, "SRDF"), path);
}

std::vector<std::string> CheckSrdf(const Srdf& srdf, const Robot& robot) {
  std::vector<std::string> warnings;
  auto where = [&](int line) {
    std::string w = srdf.source;
    if (line > 0) w.append(":").append(std::to_string(line));
    return w.append(": ");
  };
  if (!srdf.robot_name.empty() && !robot.name.empty() && srdf.robot_name != robot.name) {
    warnings.push_back(where(0) + "written for robot '" + srdf.robot_name + "', not '" +
                       robot.name + "' (" + robot.source + ")");
  }
  std::set<std::string> links, joints;
  for (const Link& l : robot.links) links.insert(l.name);
  for (const Joint& j : robot.joints) joints.insert(j.name);
  std::set<std::string> virtuals;
  for (const SrdfVirtualJoint& v : srdf.virtual_joints) {
    virtuals.insert(v.name);
    if (!v.child_link.empty() && !links.count(v.child_link)) {
      warnings.push_back(where(v.line) + "virtual_joint '" + v.name + "': child_link '" +
                         v.child_link + "' is not part of robot '" + robot.name + "' (skipped)");
    } else if (v.type != "fixed" && !robot.links.empty() && v.child_link != robot.links[0].name) {
      warnings.push_back(where(v.line) + "virtual_joint '" + v.name + "' (" + v.type +
                         ") attaches link '" + v.child_link + "', not the root link '" +
                         robot.links[0].name + "' (skipped: only the root can be a free base)");
    }
  }
  if (!robot.base_joint.empty()) virtuals.insert(robot.base_joint);
  constexpr size_t kMaxListed = 20;  // a long list is cut, with the count of the rest
  size_t unknown = 0;
  auto note = [&](const std::string& what, int line) {
    if (++unknown <= kMaxListed) {
      warnings.push_back(where(line) + what + " is not part of robot '" + robot.name +
                         "' (skipped)");
    }
  };
  for (const SrdfPair& p : srdf.disabled_pairs) {
    for (const std::string* l : {&p.link1, &p.link2}) {
      if (!links.count(*l)) note("link '" + *l + "'", p.line);
    }
  }
  for (const SrdfPose& pose : srdf.poses) {
    for (const SrdfJointValue& v : pose.joints) {
      if (!joints.count(v.joint) && !virtuals.count(v.joint)) {
        note("joint '" + v.joint + "' of group_state '" + pose.name + "'", v.line);
      }
    }
  }
  if (unknown > kMaxListed) {
    warnings.push_back(where(0) + std::to_string(unknown - kMaxListed) +
                       " more names the robot does not have (skipped)");
  }
  return warnings;
}

std::vector<std::pair<std::string, std::string>> DisabledPairs(const Srdf& srdf,
                                                               const Robot* robot) {
  std::set<std::string> links;
  if (robot != nullptr) {
    for (const Link& l : robot->links) links.insert(l.name);
  }
  std::vector<std::pair<std::string, std::string>> out;
  out.reserve(srdf.disabled_pairs.size());
  for (const SrdfPair& p : srdf.disabled_pairs) {
    if (robot != nullptr && (!links.count(p.link1) || !links.count(p.link2))) continue;
    out.emplace_back(p.link1, p.link2);
  }
  return out;
}

namespace {

// The group_state `name`; throws listing the available names when there is none.
const SrdfPose& FindPose(const Srdf& srdf, const std::string& name) {
  const SrdfPose* pose = nullptr;
  std::vector<std::string> names;
  for (const SrdfPose& p : srdf.poses) {
    if (p.name == name) pose = &p;
    names.push_back(p.name);
  }
  if (!pose) {
    std::string have;  // at most 20 names, then how many more
    for (size_t i = 0; i < names.size() && i < 20; ++i) have += (i ? ", " : "") + names[i];
    if (names.size() > 20) have += ", ... (" + std::to_string(names.size() - 20) + " more)";
    throw std::invalid_argument(srdf.source + ": no group_state named '" + name + "' (" +
                                (names.empty() ? "the SRDF has none" : "have: " + have) + ")");
  }
  return *pose;
}

}  // namespace

Eigen::VectorXd NamedPose(const Robot& robot, const Srdf& srdf, const std::string& name,
                          std::vector<std::string>* warnings) {
  const SrdfPose* pose = &FindPose(srdf, name);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  std::set<std::string> virtuals;
  for (const SrdfVirtualJoint& v : srdf.virtual_joints) virtuals.insert(v.name);
  if (!robot.base_joint.empty()) virtuals.insert(robot.base_joint);
  std::set<std::string> joints;
  for (const Joint& j : robot.joints) joints.insert(j.name);
  for (const SrdfJointValue& v : pose->joints) {
    if (virtuals.count(v.joint) || !joints.count(v.joint)) continue;  // CheckSrdf warns
    const Joint& j = robot.joints[FindJoint(robot, v.joint)];
    const size_t arity = j.dof >= 0 || j.is_mimic ? 1 : 0;
    if (arity == 0 && warnings != nullptr) {  // a fixed joint has no value to set (MoveIt skips it)
      std::string w = srdf.source;
      w.append(":").append(std::to_string(v.line)).append(": group_state '").append(name);
      w.append("' joint '").append(v.joint).append("' is fixed in the URDF: its ");
      w.append(std::to_string(v.values.size())).append(" value(s) are skipped");
      warnings->push_back(w);
      continue;
    }
    if (v.values.size() != std::max<size_t>(arity, 1)) {
      FailAt(srdf.source, v.line,
             "group_state '" + name + "' joint '" + v.joint + "': value= has " +
                 std::to_string(v.values.size()) + " numbers, the joint takes " +
                 std::to_string(std::max<size_t>(arity, 1)));
    }
    if (j.is_mimic || j.dof < 0) continue;
    const double value = v.values[0];
    if (value < j.limits.lower || value > j.limits.upper) {
      const std::string what = "group_state '" + name + "' joint '" + v.joint + "': value " +
                               base::FormatShortest(value) + " outside its limits [" +
                               base::FormatShortest(j.limits.lower) + ", " +
                               base::FormatShortest(j.limits.upper) + "]";
      if (warnings == nullptr) FailAt(srdf.source, v.line, what);
      std::string w = srdf.source;
      w.append(":").append(std::to_string(v.line)).append(": ").append(what);
      warnings->push_back(w);
    }
    q[j.dof] = value;
  }
  return q;
}

namespace {

void AddGroupDofs(const Robot& robot, const Srdf& srdf, const std::string& name, int depth,
                  std::set<int>* dofs) {
  const SrdfGroup* group = nullptr;
  for (const SrdfGroup& g : srdf.groups) {
    if (g.name == name) group = &g;
  }
  if (group == nullptr) {
    std::string have;
    for (const SrdfGroup& g : srdf.groups) have.append(have.empty() ? "" : ", ").append(g.name);
    std::string what = srdf.source;
    what.append(": no group named '").append(name).append("' (");
    what.append(have.empty() ? std::string("the SRDF has none") : "have: " + have).append(")");
    throw std::invalid_argument(what);
  }
  if (depth > 32) FailAt(srdf.source, group->line, "groups nested in a cycle at '" + name + "'");
  const auto add_joint = [&](int j) {
    if (robot.joints[j].dof >= 0) dofs->insert(robot.joints[j].dof);
  };
  for (const std::string& jn : group->joints) {
    for (size_t j = 0; j < robot.joints.size(); ++j) {
      if (robot.joints[j].name == jn) add_joint(static_cast<int>(j));
    }
  }
  for (const std::string& ln : group->links) {
    for (size_t l = 0; l < robot.links.size(); ++l) {
      if (robot.links[l].name == ln && robot.links[l].parent_joint >= 0)
        add_joint(robot.links[l].parent_joint);
    }
  }
  for (const auto& [base, tip] : group->chains) {
    int base_link = -1, tip_link = -1;
    for (size_t l = 0; l < robot.links.size(); ++l) {
      if (robot.links[l].name == base) base_link = static_cast<int>(l);
      if (robot.links[l].name == tip) tip_link = static_cast<int>(l);
    }
    if (base_link < 0 || tip_link < 0) continue;  // CheckSrdf names the unknown link
    int l = tip_link;
    while (l != base_link && robot.links[l].parent_joint >= 0) {
      const int j = robot.links[l].parent_joint;
      add_joint(j);
      l = robot.joints[j].parent_link;
    }
    if (l != base_link) {
      FailAt(srdf.source, group->line,
             "group '" + name + "': chain base '" + base + "' is not above tip '" + tip + "'");
    }
  }
  for (const std::string& sub : group->subgroups) AddGroupDofs(robot, srdf, sub, depth + 1, dofs);
}

}  // namespace

std::vector<int> GroupDofs(const Robot& robot, const Srdf& srdf, const std::string& group) {
  std::set<int> dofs;
  AddGroupDofs(robot, srdf, group, 0, &dofs);
  return {dofs.begin(), dofs.end()};
}

std::string FindSrdf(const std::string& urdf_path, const std::string& robot_name) {
  const fs::path urdf(urdf_path);
  const fs::path dirs[2] = {urdf.parent_path(), urdf.parent_path() / ".." / "srdf"};
  std::vector<std::string> names = {urdf.stem().string() + ".srdf"};
  if (!robot_name.empty()) names.push_back(robot_name + ".srdf");
  std::error_code ec;
  for (const std::string& name : names) {
    for (const fs::path& d : dirs) {
      if (fs::is_regular_file(d / name, ec)) return (d / name).lexically_normal().string();
    }
  }
  if (robot_name.empty()) return "";
  for (const fs::path& d : dirs) {
    std::vector<fs::path> candidates;
    for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec)) {
      if (it->path().extension() == ".srdf" && it->is_regular_file(ec))
        candidates.push_back(it->path());
    }
    std::sort(candidates.begin(), candidates.end());
    for (const fs::path& c : candidates) {
      try {
        if (LoadSrdf(c.string()).robot_name == robot_name) return c.lexically_normal().string();
      } catch (const std::invalid_argument&) {
        // A broken SRDF is not this robot's: it is reported when named with --srdf.
      }
    }
  }
  return "";
}

}  // namespace planning

namespace planning {

std::vector<std::string> ApplySrdfBase(const Srdf& srdf, Robot* robot) {
  std::vector<std::string> notes;
  if (robot->links.empty()) return notes;
  const std::string& root = robot->links[0].name;
  for (const SrdfVirtualJoint& v : srdf.virtual_joints) {
    if (v.type == "fixed" || v.child_link != root) continue;  // CheckSrdf warns of the others
    if (robot->base_type != BaseType::kFixed && robot->base_joint != v.name) {
      notes.push_back(srdf.source + ":" + std::to_string(v.line) + ": virtual_joint '" + v.name +
                      "' and the URDF's free base '" + robot->base_joint +
                      "' both move the root (the URDF's is used)");
      continue;
    }
    robot->base_type = v.type == "floating" ? BaseType::kFloating : BaseType::kPlanar;
    robot->base_joint = v.name;
    return notes;
  }
  if (robot->base_type != BaseType::kFixed) return notes;
  // Pinocchio's convention: a free-flyer it adds itself, named root_joint, with 7 values in the
  // group_states and no virtual_joint.
  bool urdf_has_root_joint = false;
  for (const Joint& j : robot->joints) urdf_has_root_joint |= j.name == "root_joint";
  if (urdf_has_root_joint) return notes;
  for (const SrdfPose& pose : srdf.poses) {
    for (const SrdfJointValue& v : pose.joints) {
      if (v.joint == "root_joint" && v.values.size() == 7) {
        robot->base_type = BaseType::kFloating;
        robot->base_joint = "root_joint";
        return notes;
      }
    }
  }
  return notes;
}

std::optional<Eigen::Isometry3d> NamedBasePose(const Robot& robot, const Srdf& srdf,
                                               const std::string& name) {
  const SrdfPose& pose = FindPose(srdf, name);
  if (robot.base_joint.empty()) return std::nullopt;
  for (const SrdfJointValue& v : pose.joints) {
    if (v.joint != robot.base_joint) continue;
    const std::string where = "group_state '" + name + "' joint '" + v.joint + "'";
    return BasePoseFromValues(robot.base_type, v.values,
                              srdf.source + ":" + std::to_string(v.line) + ": " + where);
  }
  return std::nullopt;
}

Eigen::Isometry3d BasePoseFromValues(BaseType type, const std::vector<double>& values,
                                     const std::string& where) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  if (type == BaseType::kPlanar && values.size() == 3) {
    pose.translation() = Eigen::Vector3d(values[0], values[1], 0.0);
    pose.linear() = Eigen::AngleAxisd(values[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return pose;
  }
  if (values.size() != 7 && values.size() != 3) {
    throw std::invalid_argument(where + ": expected " +
                                (type == BaseType::kPlanar ? std::string("x,y,theta (3 numbers)")
                                                           : std::string("x,y,z (3 numbers) or "
                                                                         "x,y,z,qx,qy,qz,qw (7)")) +
                                ", got " + std::to_string(values.size()) + " numbers");
  }
  for (double v : values) {
    if (!std::isfinite(v)) throw std::invalid_argument(where + ": values must be finite");
  }
  pose.translation() = Eigen::Vector3d(values[0], values[1], values[2]);
  if (values.size() == 7) {
    const Eigen::Quaterniond q(values[6], values[3], values[4], values[5]);
    if (!(q.norm() > 1e-6)) {
      throw std::invalid_argument(where + ": the quaternion qx,qy,qz,qw has zero length");
    }
    pose.linear() = q.normalized().toRotationMatrix();
  }
  return pose;
}

}  // namespace planning
