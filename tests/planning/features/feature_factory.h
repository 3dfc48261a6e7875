// Every Feature type, configured on the LWR4+SDH next to a ring and a ball (feature_test.cc).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "planning/collision/collision.h"
#include "planning/features/feature.h"
#include "planning/robot/robot.h"

namespace planning::testing {

struct FeatureFixture {
  Robot robot;
  Environment env;            // ring (mesh, for its chain) and a ball
  Environment primitive_env;  // ball and box only: the collision feature's FD check (see .cc)
};

// Loads the robot and places the objects (ring at (0.5, 0, 1.35), a ball near the workspace).
const FeatureFixture& SharedFixture();

struct FeatureCase {
  std::string name;
  std::unique_ptr<Feature> feature;
};

// One case per feature type (and per output variant).
std::vector<FeatureCase> AllFeatureCases(const FeatureFixture& fixture);
int NumFeatureCases();

}  // namespace planning::testing
