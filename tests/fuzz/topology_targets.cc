// Fuzz targets of the text formats read by topology/: chain CSV.
#include <sstream>
#include <stdexcept>

#include "tests/fuzz/fuzz_targets.h"
#include "topology/polyline.h"

namespace topoplan_fuzz {

int ChainCsv(const uint8_t* data, size_t size) {
  std::istringstream in(Text(data, size));
  try {
    const topology::Chain chain = topology::ParseChainCsv(in, "fuzz.csv");
    if (chain.cols() > topology::kMaxChainPoints || !chain.allFinite()) {
      throw std::logic_error("ParseChainCsv returned a chain outside its contract");
    }
  } catch (const std::invalid_argument& e) {
    Rejected(e);
  }
  return 0;
}

}  // namespace topoplan_fuzz
