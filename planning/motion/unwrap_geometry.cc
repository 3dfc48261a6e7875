#include "planning/motion/unwrap_geometry.h"

#include <Eigen/Geometry>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "base/json_reader.h"
#include "base/numbers.h"
#include "base/str_cat.h"
#include "planning/robot/pose.h"

namespace planning {
namespace {

namespace fs = std::filesystem;

// A [dim] vector of `n` with every component in [lo, hi].
Eigen::VectorXd Bounded(const base::JsonNode& n, int dim, double lo, double hi) {
  const Eigen::VectorXd v = n.Vector(dim);
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (!(v[i] >= lo && v[i] <= hi)) {
      n.Fail(base::StrCat("component ", std::to_string(i), " (", base::FormatShortest(v[i]),
                          ") out of range [", base::FormatShortest(lo), ", ",
                          base::FormatShortest(hi), "]"));
    }
  }
  return v;
}

// A geometry's name is the first column of geometry.csv, unquoted: it must be non-empty and hold
// only letters, digits, '_', '-' and '.'. `from_stem`: the name is the file's stem (no "name").
void CheckName(const std::string& name, const std::string& path, bool from_stem) {
  const auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(base::StrCat(
        path, ": name: ", from_stem ? "the file's stem (the default name) " : "", why,
        " (a geometry name is the first column of geometry.csv: letters, digits, '_', '-' and '.' "
        "only)"));
  };
  if (name.empty()) refuse("is empty");
  std::string shown = name;  // control characters as '?', so the message stays on one line
  for (char& c : shown) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  }
  for (const char c : name) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') continue;
    const bool control = static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    refuse(
        base::StrCat("'", shown, "' holds ",
                     control ? "a control character" : base::StrCat("'", std::string(1, c), "'")));
  }
}

size_t ObjectIndex(const ScenarioSpec& spec, const std::string& name) {
  for (size_t i = 0; i < spec.objects.size(); ++i) {
    if (spec.objects[i].name == name) return i;
  }
  return spec.objects.size();
}

}  // namespace

UnwrapGeometry ReadUnwrapGeometry(const std::string& path,
                                  const std::vector<std::string>& search_roots) {
  const nlohmann::json doc = base::ParseJsonFile(path, "geometry");
  const base::JsonNode root(doc, path);
  root.CheckKeys({"name", "split", "pole_tilt_deg", "pole_radius", "pole_translation",
                  "target_offset", "arm"});
  UnwrapGeometry g;
  g.source = path;
  g.name = root.String("name", fs::path(path).stem().string());
  CheckName(g.name, path, !root.Has("name"));
  g.split = root.String("split", g.split);
  if (g.split != "tuning" && g.split != "test") {
    root.At("split").Fail("expected \"tuning\" or \"test\"");
  }
  if (root.Has("pole_tilt_deg")) g.pole_tilt_deg = Bounded(root.At("pole_tilt_deg"), 2, -90, 90);
  if (root.Has("pole_radius")) g.pole_radius = root.At("pole_radius").Number(0.005, 0.5);
  if (root.Has("pole_translation"))
    g.pole_translation = Bounded(root.At("pole_translation"), 3, -1, 1);
  if (root.Has("target_offset")) g.target_offset = Bounded(root.At("target_offset"), 3, -1, 1);
  if (root.Has("arm")) {
    const base::JsonNode an = root.At("arm");
    an.CheckKeys({"urdf", "disabled_groups"});
    const base::JsonNode un = an.At("urdf");
    if (un.String().empty()) un.Fail("empty path");
    g.arm_urdf = ResolveDataFile(un.String(), fs::path(path).parent_path().string(), search_roots,
                                 un.Where());
    g.arm_urdf_where = un.Where();
    if (an.Has("disabled_groups")) {
      const base::JsonNode gs = an.At("disabled_groups");
      g.arm_disabled_groups.emplace();
      for (size_t i = 0; i < gs.Size(); ++i) g.arm_disabled_groups->push_back(gs.At(i).Strings());
      g.arm_disabled_groups_where = gs.Where();
    }
  }
  return g;
}

void ApplyUnwrapGeometry(const UnwrapGeometry& g, ScenarioSpec* spec) {
  const std::string where = base::StrCat(g.source, ": ");
  if (spec->start.kind != StartKind::kCoil) {
    throw std::invalid_argument(
        base::StrCat(where, "the scenario ", spec->source,
                     " is not an unwrap scenario (no coil start, start.coil)"));
  }
  if (!spec->writhe_report) {
    throw std::invalid_argument(
        base::StrCat(where, "the scenario ", spec->source, " has no writhe_report (the pole)"));
  }
  const std::string& pole_name = spec->writhe_report->object.name;
  const size_t pole = ObjectIndex(*spec, pole_name);
  if (pole == spec->objects.size()) {
    throw std::invalid_argument(
        base::StrCat(where, "the scenario has no object '", pole_name, "'"));
  }
  ObjectSpec& p = spec->objects[pole];
  // Tilt about the pole's own x and y axes through its origin, then translate.
  const double deg = M_PI / 180.0;
  Eigen::Isometry3d pose = PoseFromXyzRpy(p.xyz, p.rpy);
  pose.linear() =
      pose.linear() * (Eigen::AngleAxisd(g.pole_tilt_deg.x() * deg, Eigen::Vector3d::UnitX()) *
                       Eigen::AngleAxisd(g.pole_tilt_deg.y() * deg, Eigen::Vector3d::UnitY()))
                          .toRotationMatrix();
  pose.translation() += g.pole_translation;
  if (!g.pole_tilt_deg.isZero()) {
    PoseToXyzRpy(pose, &p.xyz, &p.rpy);
  } else {
    p.xyz = pose.translation();  // exactly the scenario's placement when only translated
  }
  if (g.pole_radius > 0.0) {
    p.capsule_chain = spec->writhe_report->object_chain;
    p.capsule_radius = g.pole_radius;
  }
  if (!g.target_offset.isZero()) {
    const auto fail = [&] {
      throw std::invalid_argument(
          base::StrCat(where,
                       "target_offset needs the success criterion's position task to have a target "
                       "placed in the frame of '",
                       pole_name, "' (directly or through an object placed in it)"));
    };
    if (!spec->success.position_task) fail();
    TaskSpec* reach = nullptr;
    for (TaskSpec& t : spec->tasks) {
      if (t.name == spec->success.position_task->name) reach = &t;
    }
    if (reach == nullptr || !reach->target.frame) fail();
    if (reach->target.frame->name == pole_name) {
      reach->target.value += g.target_offset;
    } else {
      const size_t o = ObjectIndex(*spec, reach->target.frame->name);
      if (o == spec->objects.size() || !spec->objects[o].frame ||
          spec->objects[o].frame->name != pole_name)
        fail();
      spec->objects[o].xyz += g.target_offset;
    }
  }
  if (!g.arm_urdf.empty()) {
    spec->robot = g.arm_urdf;
    spec->robot_where = g.arm_urdf_where;
    spec->srdf.clear();
    if (g.arm_disabled_groups) {
      spec->collision.disabled_groups = *g.arm_disabled_groups;
      spec->collision.groups_where = g.arm_disabled_groups_where;
    }
  }
}

}  // namespace planning
