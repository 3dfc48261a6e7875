#include "app/ui/panels.h"

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
    if (ImGui::SliderFloat("damping", &damping, 0.01f, 100.0f, "%.2f",
                           ImGuiSliderFlags_Logarithmic)) {
      s->planner.damping = damping;
    }
    if (ImGui::Button("Plan")) commands->emplace_back(SessionCommand::Kind::kPlan);
    Remember("Plan", rects);
    ImGui::SameLine();
    if (ImGui::Button("Step sweep")) commands->emplace_back(SessionCommand::Kind::kStep);
    Remember("Step sweep", rects);
    ImGui::SameLine();
    if (ImGui::Button("Reset")) commands->emplace_back(SessionCommand::Kind::kReset);
    Remember("Reset", rects);
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
    int frame = s->frame;
    if (ImGui::SliderInt("t", &frame, 0, frames - 1)) {
      commands->emplace_back(SessionCommand::Kind::kSeek, "", 0, static_cast<double>(frame));
    }
    Remember("timeline", rects);
    if (!session.sweeps().empty()) {
      int sweep = s->sweep;
      if (ImGui::SliderInt("sweep", &sweep, -1, static_cast<int>(session.sweeps().size()) - 1,
                           sweep < 0 ? "final" : "%d")) {
        s->sweep = sweep;
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
  if (ImGui::Button("Step")) commands->emplace_back(SessionCommand::Kind::kGraspStep, "", 0, 1.0);
  Remember("Grasp step", rects);
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
  // Cells snapped to whole pixels (deterministic across rasterisers), limits symmetric about 0.
  const double limit = std::max(1e-9, w.cwiseAbs().maxCoeff());
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
  ImGui::Text("rows: robot, |max| %.3g", limit);
  ImGui::End();
}

void CostPanel(const Session& session, const Settings& s) {
  const auto& sweeps = session.sweeps();
  if (sweeps.empty()) return;
  std::vector<float> costs;
  for (const SweepRecord& r : sweeps)
    costs.push_back(static_cast<float>(std::log10(std::max(r.cost, 1e-12))));
  ImGui::SetNextWindowPos(
      ImVec2(static_cast<float>(s.width) - 290.0f, static_cast<float>(s.height) - 150.0f),
      ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(280, 140), ImGuiCond_Always);
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
