// Numbers are read and written the same whatever locale the host program has set: every asset
// loaded through the C++ API under a comma-decimal locale (de_DE.UTF-8, made by the test fixture
// with localedef into the build tree, LOCPATH) equals the asset loaded in the "C" locale, and the
// number printers write '.'.
#include <gtest/gtest.h>

#include <clocale>
#include <filesystem>
#include <string>
#include <vector>

#include "base/assets.h"
#include "base/numbers.h"
#include "planning/grasp/grasp_inputs.h"
#include "planning/motion/planner.h"
#include "planning/motion/scenario.h"
#include "planning/robot/robot_io.h"
#include "planning/robot/srdf.h"
#include "render/figure.h"
#include "topology/polyline.h"
#include "visualize/scene_file.h"

namespace {

namespace fs = std::filesystem;

// Everything read from the assets, as numbers, for comparison.
struct Loaded {
  std::vector<double> numbers;
  void Add(double v) { numbers.push_back(v); }
  void Add(const Eigen::MatrixXd& m) {
    for (Eigen::Index i = 0; i < m.size(); ++i) numbers.push_back(m.data()[i]);
  }
};

Loaded LoadEverything() {
  Loaded out;
  const std::string root = base::AssetRoot();
  for (const auto& e : fs::recursive_directory_iterator(root + "/robots")) {
    if (e.path().extension() != ".urdf") continue;
    const planning::Robot r = planning::LoadRobot(e.path().string());
    for (const planning::Joint& j : r.joints) {
      out.Add(j.parent_from_joint.matrix());
      out.Add(j.limits.lower);
      out.Add(j.limits.upper);
    }
    const std::string srdf = planning::FindSrdf(e.path().string());
    if (!srdf.empty()) {
      for (const planning::SrdfPose& p : planning::LoadSrdf(srdf).poses) {
        for (const planning::SrdfJointValue& v : p.joints) {
          for (double x : v.values) out.Add(x);
        }
      }
    }
  }
  for (const auto& e : fs::directory_iterator(root + "/chains")) {
    out.Add(topology::ReadChainCsv(e.path().string()));
  }
  for (const char* name : {"unwrap", "reach_through_ring", "tinyarm_ring"}) {
    planning::ScenarioOverrides o;
    if (std::string(name) == "unwrap") o.start_wrap_deg = 180.0;
    const auto s = planning::LoadScenarioArg(name, o);
    out.Add(s->initial.problem.q0);
    out.Add(s->goal_q);
    for (const planning::Task& t : s->initial.problem.tasks) out.Add(t.target);
  }
  const planning::GraspInputs in =
      planning::LoadGraspInputs(planning::SelectGraspFiles("all"));
  for (const planning::HumanGrasp& g : in.grasps) out.Add(g.world_from_object.matrix());
  for (const planning::GraspObject& o : in.objects) out.Add(o.mass);
  const visualize::SceneDocument scene =
      visualize::LoadSceneFile(root + "/scenes/example.json");
  out.Add(scene.camera.fovy_deg);
  out.Add(static_cast<double>(scene.scene.shapes.size()));
  return out;
}

TEST(Locale, AssetsReadTheSameUnderACommaDecimalLocale) {
  std::setlocale(LC_ALL, "C");
  const Loaded classic = LoadEverything();
  ASSERT_NE(std::setlocale(LC_ALL, "de_DE.UTF-8"), nullptr)
      << "locale de_DE.UTF-8 missing (LOCPATH=" << (getenv("LOCPATH") ? getenv("LOCPATH") : "")
      << "; the locale_de_DE fixture makes it with localedef)";
  ASSERT_STREQ(std::localeconv()->decimal_point, ",");  // the locale is really comma-decimal
  const Loaded german = LoadEverything();
  EXPECT_GT(classic.numbers.size(), 1000u);
  EXPECT_EQ(german.numbers, classic.numbers);
  // Printed numbers are '.' too.
  EXPECT_EQ(base::FormatFixed(0.5, 2), "0.50");
  EXPECT_EQ(render::FormatNumber(-1.25, 2), "\u22121.25");
  EXPECT_EQ(base::ParseFiniteDouble("0.5"), 0.5);
  EXPECT_FALSE(base::ParseFiniteDouble("0,5").has_value());  // never the locale's comma
  std::setlocale(LC_ALL, "C");
}

}  // namespace
