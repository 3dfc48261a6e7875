// Fuzz targets: one entry function per input format, each taking arbitrary bytes.
//
// Each function feeds the bytes to the project's reader for that format (the same function the
// commands call) and returns 0. A reader may reject the input only with std::invalid_argument
// (the "bad input, exit 2" contract); any other exception, crash, sanitizer report, leak or hang
// is a finding. The same functions are built twice (tests/fuzz/CMakeLists.txt): as libFuzzer
// binaries (TOPOPLAN_FUZZ, clang) and, in every normal build, into fuzz_replay, which replays
// the files under tests/fuzz/regressions/<target>/ and tests/fuzz/seeds/<target>/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace planning {
struct Robot;
}

namespace topoplan_fuzz {

using Entry = int (*)(const uint8_t* data, size_t size);

// Chain CSV (topology::ParseChainCsv).
int ChainCsv(const uint8_t* data, size_t size);
// Render scene JSON (app::ParseSceneJson; relative files resolve against assets/scenes).
int SceneJson(const uint8_t* data, size_t size);
// Scenario JSON (planning::ParseScenarioSpec; data files resolve against assets/).
int ScenarioJson(const uint8_t* data, size_t size);
// URDF text (planning::ParseRobot with assets/robots/tinyarm/urdf as its folder, meshes loaded),
// then, when the input has a NUL byte, the bytes after it as its chain sidecar
// (planning::LoadChains).
int Urdf(const uint8_t* data, size_t size);
// Chain sidecar JSON (planning::LoadChains) against the 20-link arm of assets/robots.
int ChainsSidecar(const uint8_t* data, size_t size);
// SRDF text (planning::ParseSrdf, then planning::CheckSrdf against the tiny arm).
int Srdf(const uint8_t* data, size_t size);
// Grasp and grasp-spec files (planning::LoadHumanGrasp, then the checks LoadGraspInputs makes:
// the object exists, HumanConfiguration on the human hand).
int Grasp(const uint8_t* data, size_t size);
// Grasp object catalogue (planning::LoadGraspObjects), then signed distances of each object.
int GraspObjects(const uint8_t* data, size_t size);
// Mesh files (planning::LoadMesh, then planning::ConvexHull as collision checking uses it): the
// first line is the file's extension (stl, obj or dae; LoadMesh refuses any other, and a first line
// that is not a short alphanumeric word gives "bin"), the rest is the file.
int Mesh(const uint8_t* data, size_t size);
// PNG bytes (render::DecodePng).
int Png(const uint8_t* data, size_t size);
// Viewer scripts (app::ParseScript, the parser of `view --script`; it needs no window).
int Script(const uint8_t* data, size_t size);
// Command-line flags: the first byte picks a parser (app::ParseNumberList, app::FiniteIn,
// app::ParseImageSize, app::ParseQ, planning::ParsePlanner, ParseTransferMethod,
// render::ParseGlBackend, through app::ParseFlag), the rest is the flag's text; a leading
// byte >= 0x80 parses the rest as a whole command line, one argument per line (CLI11 with the
// commands of app_core registered, all but demo and view, without running them).
int Flags(const uint8_t* data, size_t size);

struct Target {
  const char* name;  // folder name under tests/fuzz/{regressions,seeds,dict}
  Entry entry;
};
// Every target, in the order above (defined by fuzz_replay).
const std::vector<Target>& Targets();

// The bytes as a string.
inline std::string Text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Writes the bytes to a file in this process's private temporary folder and returns its path
// ("<tmp>/topoplan-fuzz-<pid>/<name>"); readers that only take paths read it back.
std::string WriteInput(const uint8_t* data, size_t size, const std::string& name);

// Called with every std::invalid_argument a reader throws (the expected way to refuse an input):
// prints its message when TOPOPLAN_FUZZ_VERBOSE is set, to check that seeds are accepted.
void Rejected(const std::exception& e);

// assets/robots/tinyarm (meshes not loaded), read once.
const planning::Robot& TinyArm();

// <source tree>/assets/<relative>.
std::string AssetPath(const std::string& relative);

}  // namespace topoplan_fuzz
