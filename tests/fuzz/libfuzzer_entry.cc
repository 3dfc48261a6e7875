// libFuzzer entry point of one target; TOPOPLAN_FUZZ_ENTRY names its function (CMakeLists.txt).
#include "tests/fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return topoplan_fuzz::TOPOPLAN_FUZZ_ENTRY(data, size);
}
