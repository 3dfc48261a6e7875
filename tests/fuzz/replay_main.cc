// fuzz_replay: runs fuzz targets (fuzz_targets.h) on files, without libFuzzer, in a normal build.
//
//   fuzz_replay DIR...          for each DIR/<target>/FILE: the target <target> on FILE
//   fuzz_replay TARGET FILE...  that target on each FILE
// Exit 0 when every file was replayed (a crash or sanitizer report ends the process); 2 for an
// unknown target or an unreadable path.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_targets.h"

namespace topoplan_fuzz {

const std::vector<Target>& Targets() {
  static const std::vector<Target> kTargets = {{"chain_csv", &ChainCsv},
                                               {"scene_json", &SceneJson},
                                               {"scenario_json", &ScenarioJson},
                                               {"urdf", &Urdf},
                                               {"chains_sidecar", &ChainsSidecar},
                                               {"srdf", &Srdf},
                                               {"grasp", &Grasp},
                                               {"grasp_objects", &GraspObjects},
                                               {"mesh", &Mesh},
                                               {"png", &Png},
                                               {"script", &Script},
                                               {"flags", &Flags}};
  return kTargets;
}

}  // namespace topoplan_fuzz

namespace {

namespace fs = std::filesystem;
using topoplan_fuzz::Target;

const Target* FindTarget(const std::string& name) {
  for (const Target& t : topoplan_fuzz::Targets()) {
    if (name == t.name) return &t;
  }
  return nullptr;
}

bool ReplayFile(const Target& target, const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "fuzz_replay: cannot read %s\n", file.c_str());
    return false;
  }
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::fprintf(stderr, "%s %s (%zu bytes)\n", target.name, file.c_str(), bytes.size());
  target.entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  return true;
}

std::vector<fs::path> SortedFiles(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && e.path().filename().string()[0] != '.') files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: fuzz_replay DIR... | fuzz_replay TARGET FILE...\n");
    return 2;
  }
  int replayed = 0;
  if (const Target* target = FindTarget(argv[1])) {
    for (int i = 2; i < argc; ++i) {
      if (!ReplayFile(*target, argv[i])) return 2;
      ++replayed;
    }
  } else {
    for (int i = 1; i < argc; ++i) {
      if (!fs::is_directory(argv[i])) {
        std::fprintf(stderr, "fuzz_replay: %s is neither a target nor a folder\n", argv[i]);
        return 2;
      }
      for (const fs::directory_entry& sub : fs::directory_iterator(argv[i])) {
        if (!sub.is_directory()) continue;
        const Target* t = FindTarget(sub.path().filename().string());
        if (t == nullptr) {
          std::fprintf(stderr, "fuzz_replay: %s: no target of this name\n", sub.path().c_str());
          return 2;
        }
        for (const fs::path& file : SortedFiles(sub.path())) {
          if (!ReplayFile(*t, file)) return 2;
          ++replayed;
        }
      }
    }
  }
  std::printf("fuzz_replay: %d inputs replayed, no crash\n", replayed);
  return 0;
}
