// URDF → Robot: a validation pass over the XML (for clear, line-numbered messages and the file
// order of joints), then urdfdom for the model itself, planning/mesh_io for meshes, nlohmann-json
// for chains.
#include "planning/robot/robot_io.h"

#include <tinyxml.h>
#include <urdf_model/model.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "base/file_read.h"
#include "base/json_reader.h"
#include "planning/robot/chain_json.h"
#include "planning/robot/internal/package_resolver.h"
#include "planning/robot/internal/xml_text.h"
#include "planning/robot/mesh_io.h"

namespace planning {
namespace {

namespace fs = std::filesystem;
using internal::FailAt;

// ---- Validation pass ---------------------------------------------------------------------------

struct XmlJoint {
  std::string name, type, parent, child, mimic;
  int line = 0;
};

struct XmlSummary {
  std::string robot_name;
  std::vector<std::string> links;  // file order
  std::map<std::string, int> link_line;
  std::map<std::string, std::array<size_t, 2>> geometry_count;  // link → (visuals, collisions)
  std::vector<XmlJoint> joints;                                 // file order
  std::map<std::string, int> joint_line;
  std::map<std::string, std::string> parent_of;  // child link → joint name
  std::vector<std::string> warnings;             // accepted, worth saying ("FILE:LINE: ...")
};

std::string Attr(const TiXmlElement* e, const char* name) { return internal::XmlAttr(e, name); }

// Numbers in attribute `attr` of `e`: exactly `count` finite numbers (any count if 0).
void CheckNumberAttr(const TiXmlElement* e, const char* attr, int count, bool required,
                     const std::string& source, const std::string& where) {
  const char* v = e->Attribute(attr);
  if (!v) {
    if (required) FailAt(source, e->Row(), where + ": <" + e->Value() + "> needs " + attr + "=");
    return;
  }
  std::vector<double> numbers;
  if (!internal::ParseNumbers(v, count, &numbers)) {
    FailAt(source, e->Row(),
           where + ": <" + e->Value() + " " + attr + "=\"" + v + "\">: expected " +
               (count > 1 ? std::to_string(count) + " finite numbers" : "a finite number"));
  }
}

// A <visual> or <collision>: origin numbers and exactly one known shape with valid numbers, so
// that urdfdom never drops the element (it logs and skips what it cannot parse).
void ValidateGeometryElement(const TiXmlElement* e, const std::string& source,
                             const std::string& where) {
  if (const TiXmlElement* o = e->FirstChildElement("origin")) {
    CheckNumberAttr(o, "xyz", 3, false, source, where);
    CheckNumberAttr(o, "rpy", 3, false, source, where);
  }
  const TiXmlElement* g = e->FirstChildElement("geometry");
  if (!g) FailAt(source, e->Row(), where + ": missing <geometry>");
  const TiXmlElement* shape = g->FirstChildElement();
  if (!shape) FailAt(source, g->Row(), where + ": <geometry> is empty");
  const std::string type = shape->Value();
  if (type == "box") {
    CheckNumberAttr(shape, "size", 3, true, source, where);
  } else if (type == "sphere") {
    CheckNumberAttr(shape, "radius", 1, true, source, where);
  } else if (type == "cylinder") {
    CheckNumberAttr(shape, "radius", 1, true, source, where);
    CheckNumberAttr(shape, "length", 1, true, source, where);
  } else if (type == "mesh") {
    if (Attr(shape, "filename").empty()) {
      FailAt(source, shape->Row(), where + ": <mesh> needs filename=");
    }
    CheckNumberAttr(shape, "scale", 3, false, source, where);
  } else {
    FailAt(source, shape->Row(),
           where + ": unknown geometry <" + type +
               "> (expected box, sphere, cylinder or mesh; a capsule is a <cylinder> in an "
               "element whose name starts with \"capsule\")");
  }
}

// The <link> elements: unique names, at most kMaxUrdfLinks, valid geometry; at least one.
void ValidateLinks(const TiXmlElement* robot, const std::string& source, XmlSummary* s) {
  for (const TiXmlElement* e = robot->FirstChildElement("link"); e;
       e = e->NextSiblingElement("link")) {
    const std::string name = Attr(e, "name");
    if (name.empty()) FailAt(source, e->Row(), "<link> without a name");
    if (s->link_line.count(name)) {
      FailAt(source, e->Row(),
             "duplicate link '" + name + "' (first defined at line " +
                 std::to_string(s->link_line[name]) + ")");
    }
    s->link_line[name] = e->Row();
    s->links.push_back(name);
    if (s->links.size() > kMaxUrdfLinks) {
      FailAt(source, e->Row(), "more than " + std::to_string(kMaxUrdfLinks) + " links");
    }
    for (int kind = 0; kind < 2; ++kind) {
      const char* tag = kind == 0 ? "visual" : "collision";
      size_t& k = s->geometry_count[name][kind];
      for (const TiXmlElement* v = e->FirstChildElement(tag); v;
           v = v->NextSiblingElement(tag), ++k) {
        ValidateGeometryElement(v, source, "link '" + name + "' " + tag + " " + std::to_string(k));
      }
    }
  }
  if (s->links.empty()) FailAt(source, robot->Row(), "the robot has no <link>");
}

// One <joint> (after the links): a unique name, a supported type, existing distinct parent and
// child links, one parent per link, limits where needed; recorded in s->joint_line, parent_of.
XmlJoint ValidateJoint(const TiXmlElement* e, const std::string& source, XmlSummary* s) {
  XmlJoint j;
  j.line = e->Row();
  j.name = Attr(e, "name");
  j.type = Attr(e, "type");
  if (j.name.empty()) FailAt(source, j.line, "<joint> without a name");
  if (s->joint_line.count(j.name)) {
    FailAt(source, j.line,
           "duplicate joint '" + j.name + "' (first defined at line " +
               std::to_string(s->joint_line[j.name]) + ")");
  }
  s->joint_line[j.name] = j.line;
  const std::string where = "joint '" + j.name + "': ";
  if (j.type != "revolute" && j.type != "continuous" && j.type != "prismatic" &&
      j.type != "fixed" && j.type != "floating" && j.type != "planar") {
    FailAt(source, j.line,
           where + "unknown joint type '" + j.type +
               "' (expected revolute, continuous, prismatic, fixed, floating or planar)");
  }
  const TiXmlElement* parent = e->FirstChildElement("parent");
  const TiXmlElement* child = e->FirstChildElement("child");
  if (!parent || Attr(parent, "link").empty())
    FailAt(source, j.line, where + "missing <parent link=...>");
  if (!child || Attr(child, "link").empty())
    FailAt(source, j.line, where + "missing <child link=...>");
  j.parent = Attr(parent, "link");
  j.child = Attr(child, "link");
  if (!s->link_line.count(j.parent)) {
    FailAt(source, j.line, where + "parent link '" + j.parent + "' does not exist");
  }
  if (!s->link_line.count(j.child)) {
    FailAt(source, j.line, where + "child link '" + j.child + "' does not exist");
  }
  if (j.parent == j.child) FailAt(source, j.line, where + "parent and child are the same link");
  if (s->parent_of.count(j.child)) {
    FailAt(source, j.line,
           where + "link '" + j.child + "' already has parent joint '" + s->parent_of[j.child] +
               "' (a link can have only one parent)");
  }
  s->parent_of[j.child] = j.name;
  if ((j.type == "revolute" || j.type == "prismatic") && !e->FirstChildElement("limit")) {
    FailAt(source, j.line,
           where + j.type + " joint needs a <limit lower= upper= effort= velocity=>");
  }
  if (const TiXmlElement* m = e->FirstChildElement("mimic")) {
    j.mimic = Attr(m, "joint");
    if (j.mimic.empty()) FailAt(source, m->Row(), where + "<mimic> without joint=");
  }
  return j;
}

// Roots and cycles: exactly one link without a parent, and every link reachable from it.
void CheckSingleTree(const XmlSummary& s, int robot_line, const std::string& source) {
  std::vector<std::string> roots;
  for (const std::string& l : s.links) {
    if (!s.parent_of.count(l)) roots.push_back(l);
  }
  if (roots.empty())
    FailAt(source, s.link_line.at(s.links[0]), "kinematic cycle through link '" + s.links[0] + "'");
  if (roots.size() == 1) {
    // Every link has at most one parent, so a link not reachable from the single root lies on
    // a cycle (or hangs below one). Breadth-first from the root: O(links + joints).
    std::map<std::string, std::vector<std::string>> kids;
    for (const XmlJoint& j : s.joints) kids[j.parent].push_back(j.child);
    std::set<std::string> reached{roots[0]};
    std::vector<std::string> queue{roots[0]};
    for (size_t i = 0; i < queue.size(); ++i) {
      for (const std::string& c : kids[queue[i]]) {
        if (reached.insert(c).second) queue.push_back(c);
      }
    }
    for (const std::string& l : s.links) {
      if (!reached.count(l)) {
        FailAt(source, s.link_line.at(l), "kinematic cycle through link '" + l + "'");
      }
    }
  }
  if (roots.size() != 1) {
    std::string list;
    for (const std::string& r : roots) list += (list.empty() ? "" : ", ") + r;
    FailAt(source, robot_line,
           "the links must form one tree with a single root, found " +
               std::to_string(roots.size()) + " roots (" + list + "); connect them with joints");
  }
}

// Mimic chains must end at an independent joint.
void CheckMimicChains(const XmlSummary& s, const std::string& source) {
  std::map<std::string, std::string> mimic_of;
  for (const XmlJoint& j : s.joints) {
    if (!j.mimic.empty()) mimic_of[j.name] = j.mimic;
  }
  // Each joint mimics at most one: follow each chain once (0 new, 1 on the current walk, 2 ends
  // at an independent joint), O(joints).
  std::map<std::string, int> state;
  for (const XmlJoint& j : s.joints) {
    std::vector<std::string> walk;
    std::string cur = j.name;
    while (mimic_of.count(cur) && state[cur] == 0) {
      state[cur] = 1;
      walk.push_back(cur);
      cur = mimic_of[cur];
    }
    if (mimic_of.count(cur) && state[cur] == 1) {
      FailAt(source, j.line, "mimic cycle through joint '" + j.name + "'");
    }
    for (const std::string& w : walk) state[w] = 2;
  }
}

// A floating or planar joint is a free base: it must hang from the root link, and there is at most
// one (the rest of the robot is a tree below it).
void CheckFreeBase(const XmlSummary& s, const std::string& source) {
  const XmlJoint* base = nullptr;
  for (const XmlJoint& j : s.joints) {
    if (j.type != "floating" && j.type != "planar") continue;
    if (s.parent_of.count(j.parent)) {
      FailAt(source, j.line,
             "joint '" + j.name + "': a " + j.type +
                 " joint is supported only as the free base (its parent must be the root link, "
                 "the one without a parent joint), not inside the tree");
    }
    if (base != nullptr) {
      FailAt(source, j.line,
             "joint '" + j.name + "': a second free base (first: joint '" + base->name +
                 "', line " + std::to_string(base->line) + ")");
    }
    base = &j;
  }
}

XmlSummary ValidateXml(const std::string& xml, const std::string& source) {
  internal::CheckXmlUtf8(xml, source);
  internal::CheckXmlDepth(xml, source);
  TiXmlDocument doc;
  doc.Parse(xml.c_str());
  if (doc.Error()) {
    FailAt(source, doc.ErrorRow(), std::string("XML error: ") + doc.ErrorDesc());
  }
  const TiXmlElement* robot = doc.RootElement();
  if (!robot || std::string(robot->Value()) != "robot") {
    FailAt(source, robot ? robot->Row() : 0, "the root element must be <robot>");
  }
  internal::CheckSingleRoot(doc, source);
  internal::CheckNoTrailingText(xml, source);
  XmlSummary s;
  s.robot_name = Attr(robot, "name");
  ValidateLinks(robot, source, &s);
  for (const TiXmlElement* e = robot->FirstChildElement("joint"); e;
       e = e->NextSiblingElement("joint")) {
    s.joints.push_back(ValidateJoint(e, source, &s));
  }
  for (XmlJoint& j : s.joints) {
    if (!j.mimic.empty() && !s.joint_line.count(j.mimic)) {
      // As MoveIt does: the joint moves on its own (a published URDF may name a mimic master
      // that another variant of the robot has).
      std::string w = source;
      w.append(":").append(std::to_string(j.line)).append(": joint '").append(j.name);
      w.append("' mimics unknown joint '").append(j.mimic).append("' (it moves on its own)");
      s.warnings.push_back(std::move(w));
      j.mimic.clear();
    }
  }
  CheckSingleTree(s, robot->Row(), source);
  CheckFreeBase(s, source);
  CheckMimicChains(s, source);
  return s;
}

// ---- Geometry, meshes, materials ---------------------------------------------------------------

Eigen::Isometry3d ToIsometry(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return t;
}

using internal::MeshResolver;

struct GeometryBuilder {
  const urdf::ModelInterface* model;
  MeshResolver resolver;
  bool load_meshes = true;
  std::vector<Mesh>* meshes;
  std::map<std::string, int> mesh_index;

  // Returns false when the geometry is dropped (a mesh with load_meshes off).
  bool Convert(const urdf::GeometrySharedPtr& g, const std::string& element_name,
               const std::string& where, Geometry* out) {
    if (!g) FailAt(resolver.source, 0, where + ": <geometry> is missing or empty");
    switch (g->type) {
      case urdf::Geometry::SPHERE: {
        const auto& s = static_cast<const urdf::Sphere&>(*g);
        out->kind = Geometry::Kind::kSphere;
        out->size = Eigen::Vector3d(s.radius, 0, 0);
        break;
      }
      case urdf::Geometry::BOX: {
        const auto& b = static_cast<const urdf::Box&>(*g);
        out->kind = Geometry::Kind::kBox;
        out->size = Eigen::Vector3d(b.dim.x, b.dim.y, b.dim.z);
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& c = static_cast<const urdf::Cylinder&>(*g);
        out->kind = element_name.starts_with("capsule") ? Geometry::Kind::kCapsule
                                                        : Geometry::Kind::kCylinder;
        out->size = Eigen::Vector3d(c.radius, c.length, 0);
        break;
      }
      case urdf::Geometry::MESH: {
        const auto& m = static_cast<const urdf::Mesh&>(*g);
        if (!load_meshes) return false;
        out->kind = Geometry::Kind::kMesh;
        out->size = Eigen::Vector3d(m.scale.x, m.scale.y, m.scale.z);
        const std::string path = resolver.Resolve(m.filename);
        auto it = mesh_index.find(path);
        if (it == mesh_index.end()) {
          meshes->push_back(LoadMesh(path));
          it = mesh_index.emplace(path, static_cast<int>(meshes->size()) - 1).first;
        }
        out->mesh = it->second;
        break;
      }
    }
    if (out->kind == Geometry::Kind::kCapsule && !(out->size[0] > 0)) {
      FailAt(resolver.source, 0, where + ": a capsule needs a radius > 0");
    }
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(out->size[i]) ||
          (out->kind != Geometry::Kind::kMesh && out->size[i] < 0)) {
        FailAt(resolver.source, 0, where + ": invalid geometry size");
      }
    }
    return true;
  }
};

// Links in topological order: breadth-first from the root, children in joint file order.
std::vector<std::string> LinkOrder(const XmlSummary& summary) {
  std::map<std::string, std::vector<const XmlJoint*>> children;
  for (const XmlJoint& j : summary.joints) children[j.parent].push_back(&j);
  std::string root;
  for (const std::string& l : summary.links) {
    if (!summary.parent_of.count(l)) root = l;
  }
  std::vector<std::string> order{root};
  for (size_t i = 0; i < order.size(); ++i) {
    for (const XmlJoint* j : children[order[i]]) order.push_back(j->child);
  }
  return order;
}

// Joints in file order; q = the independent movable ones, also in file order.
void ConvertJoints(const urdf::ModelInterface& model, const XmlSummary& summary,
                   const std::map<std::string, int>& link_index, Robot* robot) {
  for (size_t i = 0; i < summary.joints.size(); ++i) {
    const XmlJoint& xj = summary.joints[i];
    const urdf::JointConstSharedPtr uj = model.getJoint(xj.name);
    if (!uj) FailAt(robot->source, xj.line, "urdfdom lost joint '" + xj.name + "'");
    Joint& j = robot->joints[i];
    j.name = xj.name;
    j.parent_link = link_index.at(xj.parent);
    j.child_link = link_index.at(xj.child);
    robot->links[j.child_link].parent_joint = static_cast<int>(i);
    j.parent_from_joint = ToIsometry(uj->parent_to_joint_origin_transform);
    switch (uj->type) {
      case urdf::Joint::REVOLUTE:
        j.type = JointType::kRevolute;
        break;
      case urdf::Joint::CONTINUOUS:
        j.type = JointType::kContinuous;
        break;
      case urdf::Joint::PRISMATIC:
        j.type = JointType::kPrismatic;
        break;
      case urdf::Joint::FIXED:
        j.type = JointType::kFixed;
        break;
      case urdf::Joint::FLOATING:
      case urdf::Joint::PLANAR:
        // The free base (CheckFreeBase): rigid in the model, placed by Robot::world_from_root.
        j.type = JointType::kFixed;
        robot->base_type =
            uj->type == urdf::Joint::FLOATING ? BaseType::kFloating : BaseType::kPlanar;
        robot->base_joint = xj.name;
        break;
      default:
        FailAt(robot->source, xj.line, "joint '" + xj.name + "': unsupported joint type");
    }
    if (j.type != JointType::kFixed) {
      Eigen::Vector3d a(uj->axis.x, uj->axis.y, uj->axis.z);
      if (!(a.norm() > 1e-9)) FailAt(robot->source, xj.line, "joint '" + xj.name + "': zero axis");
      j.axis = a.normalized();
    }
    if (uj->limits) {
      if (j.type == JointType::kRevolute || j.type == JointType::kPrismatic) {
        j.limits.lower = uj->limits->lower;
        j.limits.upper = uj->limits->upper;
        if (j.limits.lower > j.limits.upper) {
          FailAt(robot->source, xj.line, "joint '" + xj.name + "': lower limit > upper limit");
        }
      }
      if (uj->limits->velocity > 0) j.limits.velocity = uj->limits->velocity;
      if (uj->limits->effort > 0) j.limits.effort = uj->limits->effort;
    }
    if (uj->mimic && !xj.mimic.empty() && j.type != JointType::kFixed) {
      j.is_mimic = true;
      j.mimic_multiplier = uj->mimic->multiplier;
      j.mimic_offset = uj->mimic->offset;
    } else if (j.type != JointType::kFixed) {
      j.dof = static_cast<int>(robot->dof_joints.size());
      robot->dof_joints.push_back(static_cast<int>(i));
    }
  }
}

// Resolve mimic joints transitively to an independent master.
void ResolveMimicJoints(const XmlSummary& summary, Robot* robot) {
  std::map<std::string, int> joint_index;
  for (size_t i = 0; i < summary.joints.size(); ++i)
    joint_index[summary.joints[i].name] = static_cast<int>(i);
  for (size_t i = 0; i < robot->joints.size(); ++i) {
    Joint& j = robot->joints[i];
    if (!j.is_mimic) continue;
    double mult = j.mimic_multiplier, off = j.mimic_offset;
    int master = joint_index.at(summary.joints[i].mimic);
    while (robot->joints[master].is_mimic) {
      const Joint& m = robot->joints[master];
      off = mult * m.mimic_offset + off;
      mult = mult * m.mimic_multiplier;
      master = joint_index.at(summary.joints[master].mimic);
    }
    if (robot->joints[master].dof < 0) {
      FailAt(robot->source, summary.joints[i].line,
             "joint '" + j.name + "': mimics fixed joint '" + robot->joints[master].name + "'");
    }
    j.dof = robot->joints[master].dof;
    j.mimic_multiplier = mult;
    j.mimic_offset = off;
  }
}

}  // namespace

// ---- Chains ------------------------------------------------------------------------------------

void LoadChains(const std::string& json_path, Robot* robot) {
  const nlohmann::json doc = base::ParseJsonFile(json_path, "chain");
  const base::JsonNode root(doc, json_path);
  root.CheckKeys({"chains"});
  const base::JsonNode chains = root.At("chains");
  for (size_t c = 0; c < chains.Size(); ++c) {
    robot->chains.push_back(ResolveChain(ReadChainDescription(chains.At(c)), *robot));
  }
}

// ---- URDF --------------------------------------------------------------------------------------

Robot ParseRobot(const std::string& urdf_xml, const std::string& source_name,
                 const std::string& base_dir, const RobotLoadOptions& options) {
  const XmlSummary summary = ValidateXml(urdf_xml, source_name);
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(urdf_xml);
  if (!model) FailAt(source_name, 0, "urdfdom rejected the file (see the messages above)");

  Robot robot;
  robot.name = summary.robot_name;
  robot.source = source_name;
  robot.warnings = summary.warnings;
  const std::vector<std::string> order = LinkOrder(summary);
  std::map<std::string, int> link_index;
  for (size_t i = 0; i < order.size(); ++i) link_index[order[i]] = static_cast<int>(i);
  robot.joints.resize(summary.joints.size());
  robot.links.resize(order.size());

  const MeshResolver resolver{source_name, fs::path(base_dir), options.package_paths, {}};
  GeometryBuilder geo{model.get(), resolver, options.load_meshes, &robot.meshes, {}};
  for (size_t i = 0; i < order.size(); ++i) {
    Link& link = robot.links[i];
    link.name = order[i];
    const urdf::LinkConstSharedPtr ul = model->getLink(link.name);
    if (!ul)
      FailAt(source_name, summary.link_line.at(link.name), "urdfdom lost link '" + link.name + "'");
    const std::array<size_t, 2>& count = summary.geometry_count.at(link.name);
    if (ul->visual_array.size() != count[0] || ul->collision_array.size() != count[1]) {
      FailAt(source_name, summary.link_line.at(link.name),
             "link '" + link.name + "': urdfdom dropped a <visual> or <collision> element");
    }
    for (size_t v = 0; v < ul->visual_array.size(); ++v) {
      const urdf::Visual& vis = *ul->visual_array[v];
      Geometry g;
      const std::string where = "link '" + link.name + "' visual " + std::to_string(v);
      if (!geo.Convert(vis.geometry, vis.name, where, &g)) continue;
      g.link_from_geometry = ToIsometry(vis.origin);
      urdf::MaterialSharedPtr mat = vis.material;
      if ((!mat || mat->color.a == 0) && !vis.material_name.empty())
        mat = model->getMaterial(vis.material_name);
      if (mat) g.rgba = {mat->color.r, mat->color.g, mat->color.b, mat->color.a};
      link.visuals.push_back(g);
    }
    for (size_t c = 0; c < ul->collision_array.size(); ++c) {
      const urdf::Collision& col = *ul->collision_array[c];
      Geometry g;
      const std::string where = "link '" + link.name + "' collision " + std::to_string(c);
      if (!geo.Convert(col.geometry, col.name, where, &g)) continue;
      g.link_from_geometry = ToIsometry(col.origin);
      link.collisions.push_back(g);
    }
  }
  ConvertJoints(*model, summary, link_index, &robot);
  ResolveMimicJoints(summary, &robot);

  // Chains sidecar.
  std::string chains = options.chains_path;
  if (chains.empty() && !base_dir.empty()) {
    fs::path stem = fs::path(source_name).filename();
    stem.replace_extension(".chains.json");
    const fs::path candidate = fs::path(base_dir) / stem;
    if (fs::is_regular_file(candidate)) chains = candidate.string();
  }
  if (!chains.empty()) LoadChains(chains, &robot);
  return robot;
}

Robot LoadRobot(const std::string& urdf_path, const RobotLoadOptions& options) {
  const std::string xml = base::ReadFileBounded(urdf_path, "URDF");
  std::string dir = fs::path(urdf_path).parent_path().string();
  if (dir.empty()) dir = ".";
  return ParseRobot(xml, urdf_path, dir, options);
}

}  // namespace planning
