// `topoplan demo`: the main job. Computes every result the project can produce and writes them,
// with an index.html, into one output folder.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/assets.h"
#include "app/command.h"
#include "app/io.h"
#include "topology/polyline.h"
#include "topology/winding.h"
#include "topology/writhe.h"

namespace app {
namespace {

struct DemoArgs {
  std::string out_dir = "demo-out";
};

// Example chain pairs shipped in assets/chains/ and what their total writhe should be.
struct ChainPair {
  const char* name;
  const char* a;
  const char* b;
  const char* expected;
};
constexpr ChainPair kPairs[] = {
    {"hopf", "hopf_a.csv", "hopf_b.csv", "-1 (Hopf link, linking number)"},
    {"unlinked", "unlinked_a.csv", "unlinked_b.csv", "0 (separate rings)"},
    {"torus_2_6", "torus_2_6_a.csv", "torus_2_6_b.csv",
     "|3| ((2,6) torus link; sign = orientation)"},
    {"helix_pole", "helix_3turns.csv", "pole.csv", "about 3 (3-turn helix around a pole)"},
    {"ring_arm", "ring.csv", "arm_through_ring.csv", "about -0.9 (open arm through a ring)"},
};

int RunDemo(const DemoArgs& args) {
  namespace fs = std::filesystem;
  const fs::path out(args.out_dir);
  fs::create_directories(out / "writhe");
  std::printf("topoplan demo -> %s\n", fs::absolute(out).c_str());

  nlohmann::json summary = nlohmann::json::array();
  std::ostringstream rows;
  int index = 0;
  for (const ChainPair& p : kPairs) {
    ++index;
    const topology::Chain a = topology::ReadChainCsv(AssetPath(std::string("chains/") + p.a));
    const topology::Chain b = topology::ReadChainCsv(AssetPath(std::string("chains/") + p.b));
    const Eigen::MatrixXd w = topology::WritheMatrix(a, b);
    nlohmann::json j;
    j["rows"] = w.rows();
    j["cols"] = w.cols();
    j["total"] = w.sum();
    nlohmann::json m = nlohmann::json::array();
    for (Eigen::Index r = 0; r < w.rows(); ++r) {
      m.push_back(std::vector<double>(w.cols()));
      for (Eigen::Index c = 0; c < w.cols(); ++c) m.back()[c] = w(r, c);
    }
    j["matrix"] = std::move(m);
    const std::string file = "writhe/" + std::string(p.name) + ".json";
    WriteFileAtomic((out / file).string(), j.dump() + "\n");
    std::printf("[%d/%zu] writhe %-11s %3ldx%-3ld total %+.6f   (expected %s)\n", index,
                std::size(kPairs), p.name, static_cast<long>(w.rows()), static_cast<long>(w.cols()),
                w.sum(), p.expected);
    summary.push_back(
        {{"name", p.name}, {"a", p.a}, {"b", p.b}, {"total", w.sum()}, {"file", file}});
    char line[512];
    std::snprintf(line, sizeof line,
                  "<tr><td>%s</td><td>%s &times; %s</td><td>%ldx%ld</td><td>%+.6f</td><td>%s</td>"
                  "<td><a href=\"%s\">json</a></td></tr>\n",
                  p.name, p.a, p.b, static_cast<long>(w.rows()), static_cast<long>(w.cols()),
                  w.sum(), p.expected, file.c_str());
    rows << line;
  }
  WriteFileAtomic((out / "writhe" / "summary.json").string(), summary.dump(2) + "\n");

  std::ostringstream html;
  html << "<!doctype html><html><head><meta charset=\"utf-8\"><title>topoplan demo</title>"
          "<style>body{font-family:sans-serif;max-width:60em;margin:2em auto}"
          "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:.3em .6em}</style>"
          "</head><body><h1>topoplan demo</h1>\n<h2>Writhe of the example chains</h2>\n"
          "<table><tr><th>pair</th><th>chains</th><th>size</th><th>total writhe</th>"
          "<th>expected</th><th>matrix</th></tr>\n"
       << rows.str() << "</table>\n</body></html>\n";
  WriteFileAtomic((out / "index.html").string(), html.str());
  std::printf("wrote %s\n", (out / "index.html").c_str());
  return kExitOk;
}

}  // namespace

void AddDemoCommand(CLI::App* root, CommandList* commands) {
  auto args = std::make_shared<DemoArgs>();
  CLI::App* demo = root->add_subcommand("demo", "Run the main job: every result, with index.html");
  demo->add_option("-o,--out", args->out_dir, "output folder")->capture_default_str();
  commands->push_back({demo, [args]() { return RunDemo(*args); }});
}

}  // namespace app
