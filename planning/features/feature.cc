// The Feature base class's defaults (planning/features/feature.h). The concrete features and
// their factories live in their own files, planning/features/<name>_feature.{h,cc}.
#include "planning/features/feature.h"

namespace planning {

std::unique_ptr<FeatureData> Feature::CreateData(const Robot&) const { return nullptr; }
long Feature::collision_queries(const FeatureData*) const { return 0; }
long Feature::narrow_phase_calls(const FeatureData*) const { return 0; }
bool Feature::queries_world() const { return false; }
QueryCounts Feature::query_counts(const FeatureData*) const { return {}; }

}  // namespace planning
