// The files a grasp-transfer experiment reads (grasps, objects, human hand and LWR+SDH URDFs),
// loaded from the asset tree in one place for `grasp transfer`, the viewer session and the demo.
#pragma once

#include <string>
#include <vector>

#include "planning/grasp/grasp.h"
#include "planning/grasp/grasp_object.h"
#include "planning/robot/robot.h"

namespace planning {

struct GraspInputs {
  std::vector<GraspObject> objects;  // assets/grasps/objects.json
  Robot human;                       // assets/robots/human_hand.urdf
  Robot lwr_sdh;                     // assets/robots/lwr4_sdh.urdf
  std::vector<HumanGrasp> grasps;    // in the order of the files given
};

// Grasp files selected by `which`: "all" = every *.json directly in assets/grasps/ except
// objects.json (sorted by name), a name (assets/grasps/NAME.json) or a path to a file. Throws
// std::invalid_argument (message starts with "--grasp: ") when nothing matches.
std::vector<std::string> SelectGraspFiles(const std::string& which);

// Loads the objects, both robots and every grasp file, and checks that each grasp's object exists
// and its joints fit the human hand, so that a bad file fails before any simulation runs. Throws
// std::invalid_argument naming the file, EnvironmentError for a missing installed asset.
GraspInputs LoadGraspInputs(const std::vector<std::string>& grasp_files);

}  // namespace planning
