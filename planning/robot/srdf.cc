// SRDF reading (planning/robot/srdf.h): TinyXML after the depth pre-scan.
#include "planning/robot/srdf.h"

#include "base/numbers.h"

#include <tinyxml.h>

#include <filesystem>
#include <algorithm>
#include <set>
#include <stdexcept>

#include "planning/robot/internal/xml_text.h"
#include "base/file_read.h"

namespace planning {
namespace {

namespace fs = std::filesystem;
using internal::XmlAttr;

[[noreturn]] void Fail(const std::string& source, int line, const std::string& message) {
  throw std::invalid_argument(source + (line > 0 ? ":" + std::to_string(line) : "") + ": " +
                              message);
}

}  // namespace

Srdf ParseSrdf(const std::string& xml, const std::string& source) {
  internal::CheckXmlUtf8(xml, source);
  internal::CheckXmlDepth(xml, source);
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  if (doc.Error()) Fail(source, doc.ErrorRow(), std::string("XML error: ") + doc.ErrorDesc());
  const TiXmlElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Value()) != "robot") {
    Fail(source, robot ? robot->Row() : 0, "the root element of an SRDF must be <robot>");
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
        Fail(source, e->Row(), "<disable_collisions> needs link1= and link2=");
      }
      s.disabled_pairs.push_back(p);
    } else if (tag == "group_state") {
      SrdfPose pose{XmlAttr(e, "name"), XmlAttr(e, "group"), {}, e->Row()};
      if (pose.name.empty()) Fail(source, e->Row(), "<group_state> without a name");
      if (!pose_names.insert(pose.name).second) {
        Fail(source, e->Row(), "duplicate group_state '" + pose.name + "'");
      }
      for (const TiXmlElement* j = e->FirstChildElement("joint"); j;
           j = j->NextSiblingElement("joint")) {
        SrdfJointValue v{XmlAttr(j, "name"), {}, j->Row()};
        if (v.joint.empty())
          Fail(source, j->Row(), "group_state '" + pose.name + "': <joint> without a name");
        std::vector<double> numbers;
        if (!internal::ParseNumbers(XmlAttr(j, "value"), 0, &numbers)) {
          Fail(source, j->Row(),
               "group_state '" + pose.name + "' joint '" + v.joint +
                   "': value= must be finite numbers, got '" + XmlAttr(j, "value") + "'");
        }
        v.values = numbers;  // the arity is checked against the joint (NamedPose)
        pose.joints.push_back(v);
      }
      s.poses.push_back(pose);
    } else if (tag == "passive_joint") {
      s.passive_joints.push_back(XmlAttr(e, "name"));
    } else if (tag == "virtual_joint") {
      s.virtual_joints.push_back(XmlAttr(e, "name"));
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
  const std::set<std::string> virtuals(srdf.virtual_joints.begin(), srdf.virtual_joints.end());
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

Eigen::VectorXd NamedPose(const Robot& robot, const Srdf& srdf, const std::string& name,
                          std::vector<std::string>* warnings) {
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
  Eigen::VectorXd q = Eigen::VectorXd::Zero(num_dofs(robot));
  const std::set<std::string> virtuals(srdf.virtual_joints.begin(), srdf.virtual_joints.end());
  std::set<std::string> joints;
  for (const Joint& j : robot.joints) joints.insert(j.name);
  for (const SrdfJointValue& v : pose->joints) {
    if (virtuals.count(v.joint) || !joints.count(v.joint)) continue;  // CheckSrdf warns
    const Joint& j = robot.joints[FindJoint(robot, v.joint)];
    const size_t arity = j.dof >= 0 || j.is_mimic ? 1 : 0;
    if (v.values.size() != std::max<size_t>(arity, 1)) {
      Fail(srdf.source, v.line,
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
      if (warnings == nullptr) Fail(srdf.source, v.line, what);
      std::string w = srdf.source;
      w.append(":").append(std::to_string(v.line)).append(": ").append(what);
      warnings->push_back(w);
    }
    q[j.dof] = value;
  }
  return q;
}

std::string FindSrdf(const std::string& urdf_path) {
  const fs::path urdf(urdf_path);
  const std::string name = urdf.stem().string() + ".srdf";
  for (const fs::path& p : {urdf.parent_path() / name, urdf.parent_path() / ".." / "srdf" / name}) {
    if (fs::is_regular_file(p)) return p.lexically_normal().string();
  }
  return "";
}

}  // namespace planning
