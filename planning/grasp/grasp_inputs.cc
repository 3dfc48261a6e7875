#include "planning/grasp/grasp_inputs.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "base/assets.h"
#include "planning/robot/robot_io.h"

namespace planning {

std::vector<std::string> SelectGraspFiles(const std::string& which) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  if (which == "all") {
    for (const auto& e : fs::directory_iterator(base::AssetPath("grasps"))) {
      const fs::path& p = e.path();
      if (e.is_regular_file() && p.extension() == ".json" && p.filename() != "objects.json") {
        files.push_back(p.string());
      }
    }
    std::sort(files.begin(), files.end());
  } else if (fs::exists(which)) {
    files.push_back(which);
  } else if (which.find('/') != std::string::npos || fs::path(which).extension() == ".json") {
    throw std::invalid_argument("--grasp: " + which + ": cannot open grasp file");
  } else {
    const fs::path p = fs::path(base::AssetRoot()) / "grasps" / (which + ".json");
    if (!fs::exists(p)) {
      throw std::invalid_argument("--grasp: no grasp file '" + which + "' (looked for " +
                                  p.string() + ")");
    }
    files.push_back(p.string());
  }
  return files;
}

GraspInputs LoadGraspInputs(const std::vector<std::string>& grasp_files) {
  GraspInputs in;
  in.objects = LoadGraspObjects(base::AssetPath("grasps/objects.json"));
  in.human = LoadRobot(base::AssetPath("robots/human_hand.urdf"));
  in.lwr_sdh = LoadRobot(base::AssetPath("robots/lwr4_sdh.urdf"));
  for (const std::string& f : grasp_files) {
    HumanGrasp g = LoadHumanGrasp(f);
    try {
      FindGraspObject(in.objects, g.object);
      HumanConfiguration(in.human, g);
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      throw std::invalid_argument(what.rfind(f, 0) == 0 ? what : f + ": " + what);
    }
    in.grasps.push_back(std::move(g));
  }
  return in;
}

}  // namespace planning
