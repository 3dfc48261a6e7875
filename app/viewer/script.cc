// The viewer's script language (--script FILE) and its status file: ParseScript, WriteStatusJson.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/viewer/session.h"
#include "base/file_read.h"
#include "base/numbers.h"

namespace app {

namespace {

struct VerbSpec {
  const char* verb;
  int min_args, max_args;
  const char* usage;
};

// Every script verb with its argument counts and usage.
const std::vector<VerbSpec>& ScriptVerbs() {
  static const std::vector<VerbSpec> kVerbs = {
      {"load", 1, 1, "load PATH"},
      {"plan", 0, 1, "plan [async]"},
      {"step", 0, 1, "step [N]"},
      {"wait", 0, 0, "wait"},
      {"cancel", 0, 0, "cancel"},
      {"rrt_step", 1, 1, "rrt_step N"},
      {"sim_step", 1, 1, "sim_step N"},
      {"sim_phase", 0, 1, "sim_phase [N]"},
      {"move", 4, 4, "move OBJECT X Y Z"},
      {"status", 1, 1, "status FILE"},
      {"play", 0, 0, "play"},
      {"pause", 0, 0, "pause"},
      {"seek", 1, 1, "seek SECONDS"},
      {"joint", 2, 2, "joint INDEX ANGLE"},
      {"reset", 0, 0, "reset"},
      {"toggle", 1, 1, "toggle NAME"},
      {"planner", 1, 1, "planner NAME"},
      {"seed", 1, 1, "seed N"},
      {"damping", 1, 1, "damping LAMBDA"},
      {"camera", 3, 6, "camera YAW PITCH DISTANCE [TX TY TZ]"},
      {"frames", 1, 1, "frames N"},
      {"screenshot", 1, 1, "screenshot PATH"},
      {"click", 1, 1, "click WIDGET"},
      {"grasp", 2, 2, "grasp NAME METHOD"},
      {"grasp_step", 1, 1, "grasp_step N"},
      {"quit", 0, 0, "quit"}};
  return kVerbs;
}

// The arguments of a script line, checked when the script is read (the viewer converts them
// later): "frames" an integer in [1, kMaxScriptFrames] (and all frames lines together at most
// kMaxScriptTotalFrames), "seed" an integer in [0, 2^32 − 1], "damping" a number in [0, 1e6],
// step/rrt_step/sim_step N in [1, 1e6], sim_phase N in [1, 7], "joint" an index in [0, 1e6] and a
// finite value, camera/seek/grasp_step/move finite numbers that fit a float; names from their fixed
// lists.
void CheckScriptArgs(const std::string& path, const ScriptLine& l, long long* total_frames) {
  const std::string at = path + ":" + std::to_string(l.line) + ": ";
  const auto where = [&](size_t i) { return at + "'" + l.args[i] + "'"; };
  const auto number = [&](size_t i, double lo, double hi) {
    const std::optional<double> v = base::ParseFiniteDouble(l.args[i]);
    if (!v) throw std::invalid_argument(where(i) + " is not a finite number");
    if (*v < lo || *v > hi) {
      std::ostringstream range;
      range << "[" << lo << ", " << hi << "]";
      throw std::invalid_argument(where(i) + " is out of range " + range.str());
    }
    return *v;
  };
  const auto integer = [&](size_t i, double lo, double hi) {
    const double v = number(i, lo, hi);
    if (v != std::floor(v)) throw std::invalid_argument(where(i) + " is not an integer");
    return static_cast<long long>(v);
  };
  const auto one_of = [&](size_t i, const char* what, const std::vector<std::string>& choices) {
    if (std::find(choices.begin(), choices.end(), l.args[i]) == choices.end()) {
      throw std::invalid_argument(at + "unknown " + what + " '" + l.args[i] + "' " +
                                  ValidChoices(choices));
    }
  };
  if (l.verb == "frames") {
    *total_frames += integer(0, 1, kMaxScriptFrames);
    if (*total_frames > kMaxScriptTotalFrames) {
      throw std::invalid_argument(at + "more than " + std::to_string(kMaxScriptTotalFrames) +
                                  " frames in the script (limit)");
    }
  } else if (l.verb == "seed") {
    integer(0, 0, 4294967295.0);
  } else if (l.verb == "damping") {
    number(0, 0.0, 1e6);
  } else if (l.verb == "joint") {
    integer(0, 0, 1e6);
    number(1, -1e6, 1e6);
  } else if (l.verb == "camera") {
    if (l.args.size() != 3 && l.args.size() != 6) {
      throw std::invalid_argument(
          at + "'camera' takes 3 or 6 arguments: " + "camera YAW PITCH DISTANCE [TX TY TZ]");
    }
    number(0, -1e6, 1e6);
    number(1, -1e6, 1e6);
    number(2, 1e-6, 1e6);
    for (size_t i = 3; i < l.args.size(); ++i) number(i, -1e6, 1e6);
  } else if (l.verb == "seek" || l.verb == "grasp_step") {
    number(0, -1e9, 1e9);
  } else if (l.verb == "step" || l.verb == "rrt_step" || l.verb == "sim_step") {
    if (!l.args.empty()) integer(0, 1, 1e6);
  } else if (l.verb == "sim_phase") {
    if (!l.args.empty()) integer(0, 1, planning::physics::StabilityRun::kNumPhases);
  } else if (l.verb == "move") {
    for (size_t i = 1; i < 4; ++i) number(i, -1e6, 1e6);
  } else if (l.verb == "plan") {
    if (!l.args.empty()) one_of(0, "plan mode", {"async"});
  } else if (l.verb == "toggle") {
    one_of(0, "toggle", ScriptToggles());
  } else if (l.verb == "planner") {
    std::vector<std::string> names;
    for (planning::Planner p : planning::AvailablePlanners()) {
      names.push_back(planning::PlannerName(p));
    }
    one_of(0, "planner", names);
  } else if (l.verb == "grasp") {
    one_of(1, "transfer method", {"winding", "joint", "fingertip"});
  }
}

}  // namespace

std::string ValidChoices(const std::vector<std::string>& choices) {
  std::string s = "(valid: ";
  for (size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
  return s + ")";
}

const std::vector<std::string>& ScriptToggles() {
  static const std::vector<std::string> kToggles = {"chains",   "collision", "grid",
                                                    "contacts", "heatmap",   "cost"};
  return kToggles;
}

std::vector<ScriptLine> ParseScript(const std::string& path) {
  std::istringstream in(base::ReadFileBounded(path, "script"));
  const std::vector<VerbSpec>& verbs = ScriptVerbs();
  std::vector<ScriptLine> lines;
  std::string raw;
  int n = 0;
  long long total_frames = 0;
  while (std::getline(in, raw)) {
    ++n;
    std::istringstream ss(raw);
    ScriptLine l;
    l.file = path;
    l.line = n;
    if (!(ss >> l.verb) || l.verb[0] == '#') continue;
    for (std::string a; ss >> a;) l.args.push_back(a);
    const auto it = std::find_if(verbs.begin(), verbs.end(),
                                 [&](const VerbSpec& v) { return v.verb == l.verb; });
    const std::string at = path + ":" + std::to_string(n) + ": ";
    if (it == verbs.end()) {
      std::vector<std::string> names;
      for (const VerbSpec& v : verbs) names.push_back(v.verb);
      throw std::invalid_argument(at + "unknown command '" + l.verb + "' " + ValidChoices(names));
    }
    const int argc = static_cast<int>(l.args.size());
    if (argc < it->min_args || argc > it->max_args) {
      const std::string count =
          it->min_args == it->max_args
              ? std::to_string(it->min_args)
              : std::to_string(it->min_args) + " to " + std::to_string(it->max_args);
      throw std::invalid_argument(at + "'" + l.verb + "' takes " + count + " argument(s), got " +
                                  std::to_string(argc) + ": " + it->usage);
    }
    CheckScriptArgs(path, l, &total_frames);
    lines.push_back(std::move(l));
  }
  return lines;
}

void WriteStatusJson(const std::string& path, const std::string& planner, const WorkerStatus& st,
                     const FrameStats& frames) {
  nlohmann::json j;
  j["planner"] = planner;
  j["planning"] = st.computing && st.job != "grasp";  // plan, step, rrt_step, move
  j["held"] = st.held;
  j["job"] = st.job;
  j["sweep"] = st.sweep;
  j["max_sweeps"] = st.max_sweeps;
  j["cost"] = st.cost;
  j["rrt_nodes"] = st.rrt_nodes;
  j["rrt_checks"] = st.rrt_checks;
  j["sim_time_s"] = st.sim_time_s;
  j["frame_ms"] = frames.frame_ms;
  j["frame_planning"] = frames.frame_planning;
  j["frames"] = frames.frames;
  j["frames_while_planning"] = frames.frames_while_planning;
  j["scene_renders"] = frames.scene_renders;
  const std::string tmp = path + ".tmp";
  {
    std::ofstream f(tmp);
    f << j.dump(1) << "\n";
    if (!f) throw std::invalid_argument("status: cannot write '" + path + "'");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::invalid_argument("status: cannot write '" + path + "': " + ec.message());
}

}  // namespace app
