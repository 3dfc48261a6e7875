#include "app/viewer/panels.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace app::ui {
namespace {

void Remember(const char* name, WidgetRects* rects) {
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
  rects->rects[name] = {a.x, a.y, b.x, b.y};
}

// Diverging blue-white-red for v in [-1, 1] (the same anchors as the offscreen heatmaps).
ImU32 Diverging(float v) {
  v = std::clamp(v, -1.0f, 1.0f);
  const float t = std::abs(v);
  const ImVec4 white(0.97f, 0.97f, 0.97f, 1.0f);
  const ImVec4 end = v < 0 ? ImVec4(0.02f, 0.19f, 0.38f, 1.0f) : ImVec4(0.40f, 0.0f, 0.12f, 1.0f);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(white.x + t * (end.x - white.x),
                                               white.y + t * (end.y - white.y),
                                               white.z + t * (end.z - white.z), 1.0f));
}

// The worker's progress (sweep k of max and cost; simulated time) and its Cancel button, shown
// while a job runs or holds between steps.
void ProgressRow(const Session& session, const Settings& s, std::vector<SessionCommand>* commands,
                 WidgetRects* rects) {
  const WorkerStatus w = session.worker_status(s);
  if (w.job.empty()) return;
  char text[96];
  float fraction = 0.0f;
  if (w.job == "grasp") {
    std::snprintf(text, sizeof text, "t %.3f s%s", w.sim_time_s, w.held ? " (held)" : "");
    fraction = static_cast<float>(std::min(1.0, w.sim_time_s / 12.5));
  } else if (w.rrt_nodes > 0 || w.job == "rrt_step") {
    std::snprintf(text, sizeof text, "%ld nodes, checks %ld/%ld%s", w.rrt_nodes, w.rrt_checks,
                  w.rrt_budget, w.held ? " (held)" : "");
    fraction = w.rrt_budget > 0
                   ? static_cast<float>(w.rrt_checks) / static_cast<float>(w.rrt_budget)
                   : 0.0f;
  } else {
    if (w.sweep == 0 && !w.held) {  // set-up and first sweep: no cost yet
      std::snprintf(text, sizeof text, "starting: sweep 0/%d", w.max_sweeps);
    } else {
      std::snprintf(text, sizeof text, "sweep %d/%d, cost %.3g%s", w.sweep, w.max_sweeps, w.cost,
                    w.held ? " (held)" : "");
    }
    fraction =
        w.max_sweeps > 0 ? static_cast<float>(w.sweep) / static_cast<float>(w.max_sweeps) : 0.0f;
  }
  ImGui::ProgressBar(std::clamp(fraction, 0.0f, 1.0f), ImVec2(-70.0f, 0.0f), text);
  Remember("progress", rects);
  ImGui::SameLine();
  if (ImGui::Button("Cancel")) commands->emplace_back(SessionCommand::Kind::kCancel);
  Remember("Cancel", rects);
}

void ScenarioPanel(const Session& session, const std::vector<std::string>& scenarios, Settings* s,
                   std::vector<SessionCommand>* commands, WidgetRects* rects) {
  ImGui::SetNextWindowPos(ImVec2(10, 10), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_Always);
  ImGui::Begin("topoplan", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  if (ImGui::BeginCombo("scenario", s->scenario_path.c_str())) {
    for (const std::string& name : scenarios) {
      if (ImGui::Selectable(name.c_str(), name == s->scenario_path)) {
        commands->emplace_back(SessionCommand::Kind::kLoad, name);
      }
    }
    ImGui::EndCombo();
  }
  Remember("scenario", rects);

  // Planner -------------------------------------------------------------------------------------
  if (session.has_scenario()) {
    ImGui::Separator();
    ImGui::TextDisabled("planner");
    const char* planners[] = {"aico", "rrt", "birrt"};
    int current = 0;
    for (int i = 0; i < 3; ++i) {
      if (s->planner.planner == planners[i]) current = i;
    }
    if (ImGui::Combo("planner", &current, planners, 3)) s->planner.planner = planners[current];
    int seed = static_cast<int>(s->planner.seed);
    if (ImGui::InputInt("seed", &seed)) s->planner.seed = static_cast<unsigned>(std::max(0, seed));
    ImGui::SliderInt("sweeps", &s->planner.max_iterations, 1, 100);
    float damping = static_cast<float>(s->planner.damping);
    // A drag field: its value text has no slider grab drawn over it.
    if (ImGui::DragFloat("damping", &damping, 0.01f, 0.01f, 100.0f, "%.2f",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp)) {
      s->planner.damping = damping;
    }
    Remember("damping", rects);
    if (ImGui::Button("Plan")) commands->emplace_back(SessionCommand::Kind::kPlanAsync);
    Remember("Plan", rects);
    ImGui::SameLine();
    if (ImGui::Button("Step sweep"))
      commands->emplace_back(SessionCommand::Kind::kStep, "", 0, 1.0);
    Remember("Step sweep", rects);
    ImGui::SameLine();
    if (ImGui::Button("Reset")) commands->emplace_back(SessionCommand::Kind::kReset);
    Remember("Reset", rects);
    if (s->planner.planner == "rrt" || s->planner.planner == "birrt") {
      ImGui::SameLine();
      if (ImGui::Button("Step 50")) {
        commands->emplace_back(SessionCommand::Kind::kRrtStep, "", 0, 50.0);
      }
      Remember("Rrt step", rects);
    }
    ProgressRow(session, *s, commands, rects);
  }

  // Timeline ------------------------------------------------------------------------------------
  const int frames = session.num_frames(*s);
  if (frames > 0) {
    ImGui::Separator();
    ImGui::TextDisabled("timeline");
    if (ImGui::Button(s->playing ? "Pause" : "Play")) {
      commands->emplace_back(s->playing ? SessionCommand::Kind::kPause
                                        : SessionCommand::Kind::kPlay);
    }
    Remember("Play", rects);
    ImGui::SameLine();
    const double dt = session.ShownDt(*s);
    float t = static_cast<float>(s->frame * dt);
    if (ImGui::SliderFloat("t [s]", &t, 0.0f, static_cast<float>((frames - 1) * dt), "%.2f s")) {
      commands->emplace_back(SessionCommand::Kind::kSeek, "", 0, static_cast<double>(t));
    }
    Remember("timeline", rects);
    if (!session.sweeps().empty()) {
      // Sweeps counted from 1 like the progress row; 0 = the final result.
      int shown = s->sweep + 1;
      if (ImGui::SliderInt("sweep", &shown, 0, static_cast<int>(session.sweeps().size()),
                           shown == 0 ? "final" : "%d")) {
        s->sweep = shown - 1;
        s->frame = std::min(s->frame, session.num_frames(*s) - 1);
      }
    }
  }

  // Joints --------------------------------------------------------------------------------------
  if (session.loaded() && ImGui::CollapsingHeader("joints")) {
    const std::vector<std::string> names = session.joint_names();
    const Eigen::VectorXd q = session.ShownQ(*s);
    const Eigen::VectorXd lo = planning::LowerLimits(session.robot());
    const Eigen::VectorXd hi = planning::UpperLimits(session.robot());
    for (int i = 0; i < static_cast<int>(names.size()); ++i) {
      float v = static_cast<float>(q(i));
      const float a = std::isfinite(lo(i)) ? static_cast<float>(lo(i)) : -3.1416f;
      const float b = std::isfinite(hi(i)) ? static_cast<float>(hi(i)) : 3.1416f;
      if (ImGui::SliderFloat(names[i].c_str(), &v, a, b, "%.3f")) {
        commands->emplace_back(SessionCommand::Kind::kSetJoint, "", i, v);
      }
    }
  }

  // View ----------------------------------------------------------------------------------------
  ImGui::Separator();
  ImGui::TextDisabled("view");
  ImGui::Checkbox("chains", &s->view.chains);
  Remember("chains", rects);
  ImGui::SameLine();
  ImGui::Checkbox("collision", &s->view.collision_geometry);
  Remember("collision", rects);
  ImGui::SameLine();
  ImGui::Checkbox("grid", &s->view.grid);
  Remember("grid", rects);
  ImGui::Checkbox("heatmap", &s->view.heatmap_panel);
  ImGui::SameLine();
  ImGui::Checkbox("cost plot", &s->view.cost_panel);
  if (ImGui::Button("Frame camera")) s->camera_initialised = false;
  if (const planning::Scenario* sc = session.scenario(); sc && !sc->spec.objects.empty()) {
    ImGui::SameLine();
    const std::string current =
        s->move.object.empty() ? sc->spec.objects.front().name : s->move.object;
    ImGui::SetNextItemWidth(100.0f);
    if (ImGui::BeginCombo("Shift+drag", current.c_str())) {
      for (const planning::ObjectSpec& o : sc->spec.objects) {
        if (ImGui::Selectable(o.name.c_str(), o.name == current)) s->move.object = o.name;
      }
      ImGui::EndCombo();
    }
  }
  ImGui::TextWrapped("%s", session.status().c_str());
  ImGui::End();
}

void GraspPanel(const Session& session, const std::vector<std::string>& grasps, Settings* s,
                std::vector<SessionCommand>* commands, WidgetRects* rects) {
  ImGui::SetNextWindowPos(ImVec2(10, static_cast<float>(s->height) - 200.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(330, 0), ImGuiCond_Always);
  ImGui::Begin("grasp stability (ODE)", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  if (ImGui::BeginCombo("grasp", s->grasp.grasp.c_str())) {
    for (const std::string& g : grasps) {
      if (ImGui::Selectable(g.c_str(), g == s->grasp.grasp)) s->grasp.grasp = g;
    }
    ImGui::EndCombo();
  }
  const char* methods[] = {"winding", "joint", "fingertip"};
  int m = 0;
  for (int i = 0; i < 3; ++i) {
    if (s->grasp.method == methods[i]) m = i;
  }
  if (ImGui::Combo("method", &m, methods, 3)) s->grasp.method = methods[m];
  if (ImGui::Button("Transfer + test")) commands->emplace_back(SessionCommand::Kind::kGraspRun);
  Remember("Transfer + test", rects);
  ImGui::SameLine();
  // One recorded frame's worth (20 ms) of the live simulation.
  if (ImGui::Button("Step")) commands->emplace_back(SessionCommand::Kind::kSimStep, "", 0, 20.0);
  Remember("Grasp step", rects);
  ImGui::SameLine();
  // To the end of the protocol phase being simulated (closing, then each gravity direction).
  if (ImGui::Button("Step phase")) {
    commands->emplace_back(SessionCommand::Kind::kSimPhase, "", 0, 1.0);
  }
  Remember("Step_phase", rects);  // one word: `click Step_phase`
  ImGui::SameLine();
  ImGui::Checkbox("show", &s->grasp.active);
  if (const auto& g = session.grasp(); g && !g->frames.empty()) {
    int f = s->grasp.frame;
    if (ImGui::SliderInt("frame", &f, 0, static_cast<int>(g->frames.size()) - 1)) {
      s->grasp.frame = f;
      s->grasp.active = true;
    }
    const GraspReplay::Frame& fr = g->frames[std::clamp<size_t>(f, 0, g->frames.size() - 1)];
    static const char* kPhase[] = {"closing", "+x", "-x", "+y", "-y", "+z", "-z"};
    ImGui::Text("t %.2f s, gravity %s, %zu contacts", fr.state.time,
                kPhase[std::clamp(fr.phase, 0, 6)], fr.state.contacts.size());
    ImGui::Text("%s/%s: %d/6 held%s", g->grasp.c_str(), g->method.c_str(),
                g->result.directions_passed, g->result.stable ? ", stable" : "");
  }
  ImGui::End();
}

void HeatmapPanel(const Session& session, const Settings& s) {
  const Eigen::MatrixXd w = session.WritheAt(session.ShownQ(s));
  if (w.size() == 0) return;
  ImGui::SetNextWindowPos(ImVec2(static_cast<float>(s.width) - 230.0f, 10), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(220, 0), ImGuiCond_Always);
  ImGui::Begin("writhe matrix", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  ImGui::Text("%ldx%ld  total %+.3f (%.0f deg)", static_cast<long>(w.rows()),
              static_cast<long>(w.cols()), w.sum(), 360.0 * std::abs(w.sum()));
  // Cells snapped to whole pixels (deterministic across rasterisers); one symmetric range for the
  // whole shown trajectory, so colours do not rescale while it plays.
  const double limit = session.HeatmapLimit(s);
  const int max_side = 200;
  const int cell_w = std::max(1, max_side / static_cast<int>(w.cols()));
  const int cell_h = std::max(1, std::min(cell_w * 4, max_side / static_cast<int>(w.rows())));
  ImVec2 p = ImGui::GetCursorScreenPos();
  p.x = std::floor(p.x);
  p.y = std::floor(p.y);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  for (int i = 0; i < w.rows(); ++i) {
    for (int j = 0; j < w.cols(); ++j) {
      const ImVec2 a(p.x + static_cast<float>(j * cell_w), p.y + static_cast<float>(i * cell_h));
      dl->AddRectFilled(a,
                        ImVec2(a.x + static_cast<float>(cell_w), a.y + static_cast<float>(cell_h)),
                        Diverging(static_cast<float>(w(i, j) / limit)));
    }
  }
  ImGui::Dummy(
      ImVec2(static_cast<float>(cell_w * w.cols()), static_cast<float>(cell_h * w.rows())));
  // Colour bar: −limit .. 0 .. +limit, in whole-pixel columns.
  const float bar_w = static_cast<float>(cell_w * w.cols());
  ImVec2 b = ImGui::GetCursorScreenPos();
  b.x = std::floor(b.x);
  b.y = std::floor(b.y);
  const int columns = std::max(2, static_cast<int>(bar_w));
  for (int i = 0; i < columns; ++i) {
    const float v = -1.0f + 2.0f * (static_cast<float>(i) + 0.5f) / static_cast<float>(columns);
    dl->AddRectFilled(ImVec2(b.x + static_cast<float>(i), b.y),
                      ImVec2(b.x + static_cast<float>(i + 1), b.y + 10.0f), Diverging(v));
  }
  ImGui::Dummy(ImVec2(bar_w, 10.0f));
  char lo[32], hi[32];
  std::snprintf(lo, sizeof lo, "%+.3g", -limit);
  std::snprintf(hi, sizeof hi, "%+.3g", limit);
  const float y = std::floor(ImGui::GetCursorScreenPos().y);
  const ImU32 ink = ImGui::GetColorU32(ImGuiCol_Text);
  dl->AddText(ImVec2(b.x, y), ink, lo);
  dl->AddText(ImVec2(std::floor(b.x + 0.5f * bar_w - 0.5f * ImGui::CalcTextSize("0").x), y), ink,
              "0");
  dl->AddText(ImVec2(std::floor(b.x + bar_w - ImGui::CalcTextSize(hi).x), y), ink, hi);
  ImGui::Dummy(ImVec2(bar_w, ImGui::GetTextLineHeight()));
  ImGui::TextWrapped("rows: robot links; colours fixed over the trajectory");
  ImGui::End();
}

void CostPanel(const Session& session, const Settings& s) {
  const auto& sweeps = session.sweeps();
  if (sweeps.empty()) return;
  std::vector<float> costs;
  for (const SweepRecord& r : sweeps)
    costs.push_back(static_cast<float>(std::log10(std::max(r.cost, 1e-12))));
  // Anchored at its bottom-right corner and sized to its content (no clipped rows).
  ImGui::SetNextWindowPos(
      ImVec2(static_cast<float>(s.width) - 10.0f, static_cast<float>(s.height) - 10.0f),
      ImGuiCond_Always, ImVec2(1.0f, 1.0f));
  ImGui::SetNextWindowSize(ImVec2(280, 0), ImGuiCond_Always);
  ImGui::Begin("cost per sweep", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize);
  char label[64];
  std::snprintf(label, sizeof label, "last %.4g", sweeps.back().cost);
  ImGui::PlotLines("##cost", costs.data(), static_cast<int>(costs.size()), 0, label, FLT_MAX,
                   FLT_MAX, ImVec2(264, 90));
  ImGui::Text("log10 cost, %zu sweeps", sweeps.size());
  ImGui::End();
}

}  // namespace

void DrawPanels(const Session& session, const std::vector<std::string>& scenarios,
                const std::vector<std::string>& grasps, Settings* settings,
                std::vector<SessionCommand>* commands, WidgetRects* rects) {
  ScenarioPanel(session, scenarios, settings, commands, rects);
  if (!grasps.empty()) GraspPanel(session, grasps, settings, commands, rects);
  if (settings->grasp.active) return;  // the grasp view has no writhe or cost to show
  if (settings->view.heatmap_panel) HeatmapPanel(session, *settings);
  if (settings->view.cost_panel) CostPanel(session, *settings);
}

}  // namespace app::ui
