#include "app/ui/viewer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <algorithm>
#include <cfloat>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/assets.h"
#include "app/frame.h"
#include "app/session.h"
#include "app/ui/imgui_overlay.h"
#include "app/ui/panels.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/overlay.h"
#include "render/renderer.h"

namespace app::ui {
namespace {

std::vector<std::string> ListGrasps() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(AssetRoot()) / "grasps", ec)) {
    if (e.path().extension() == ".json" && e.path().filename() != "objects.json") {
      names.push_back(e.path().stem().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::string> ListScenarios() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(AssetRoot()) / "scenarios", ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Runs `--script` lines one frame at a time: session commands immediately, `frames N` waits N
// frames, `click NAME` presses the named widget on the next frame and releases it on the one after,
// `screenshot PATH` saves the frame being drawn.
class ScriptRunner {
 public:
  explicit ScriptRunner(std::vector<ScriptLine> lines) : lines_(std::move(lines)) {}
  bool done() const { return next_ >= lines_.size() && wait_ == 0 && click_phase_ == 0; }
  bool quit() const { return quit_; }

  // Before ImGui::NewFrame: consumes lines up to the next wait; sets the scripted mouse.
  void BeforeFrame(const WidgetRects& rects, Session* session, Settings* settings,
                   std::vector<std::string>* screenshots, ImGuiIO* io) {
    screenshots->clear();
    if (click_phase_ == 1) {  // press
      io->MousePos = click_pos_;
      io->MouseDown[0] = true;
      click_phase_ = 2;
      return;
    }
    if (click_phase_ == 2) {  // release
      io->MousePos = click_pos_;
      io->MouseDown[0] = false;
      click_phase_ = 3;
      return;
    }
    if (click_phase_ == 3) {  // move away so nothing stays hovered
      io->MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
      click_phase_ = 0;
    }
    if (wait_ > 0) {
      --wait_;
      return;
    }
    // The first frame lays out the widgets that `click` aims at.
    if (rects.rects.empty()) return;
    while (next_ < lines_.size()) {
      const ScriptLine& l = lines_[next_++];
      const auto arg = [&](size_t i) { return l.args.at(i); };
      const auto num = [&](size_t i) {
        try {
          return std::stod(arg(i));
        } catch (const std::exception&) {
          throw std::invalid_argument("script line " + std::to_string(l.line) + ": '" + arg(i) +
                                      "' is not a number");
        }
      };
      if (l.verb == "quit") {
        quit_ = true;
        return;
      } else if (l.verb == "frames") {
        wait_ = std::max(0, static_cast<int>(num(0)) - 1);
        return;
      } else if (l.verb == "screenshot") {
        screenshots->push_back(arg(0));
        return;
      } else if (l.verb == "click") {
        const auto it = rects.rects.find(arg(0));
        if (it == rects.rects.end()) {
          throw std::invalid_argument("script line " + std::to_string(l.line) + ": no widget '" +
                                      arg(0) + "' on screen");
        }
        const WidgetRects::Rect& r = it->second;
        click_pos_ = ImVec2(0.5f * (r.x0 + r.x1), 0.5f * (r.y0 + r.y1));
        io->MousePos = click_pos_;  // hover first, press on the next frame
        click_phase_ = 1;
        return;
      } else if (l.verb == "toggle") {
        ViewToggles& v = settings->view;
        const std::string& what = arg(0);
        bool* flag = what == "chains"      ? &v.chains
                     : what == "collision" ? &v.collision_geometry
                     : what == "grid"      ? &v.grid
                     : what == "contacts"  ? &v.contacts
                     : what == "heatmap"   ? &v.heatmap_panel
                     : what == "cost"      ? &v.cost_panel
                                           : nullptr;
        if (!flag) {
          throw std::invalid_argument("script line " + std::to_string(l.line) +
                                      ": unknown toggle '" + what + "'");
        }
        *flag = !*flag;
      } else if (l.verb == "planner") {
        settings->planner.planner = arg(0);
      } else if (l.verb == "seed") {
        settings->planner.seed = static_cast<unsigned>(num(0));
      } else if (l.verb == "camera") {
        settings->camera.yaw_deg = static_cast<float>(num(0));
        settings->camera.pitch_deg = static_cast<float>(num(1));
        settings->camera.distance = static_cast<float>(num(2));
        settings->camera_initialised = true;
      } else {
        SessionCommand c;
        using K = SessionCommand::Kind;
        if (l.verb == "load") c = SessionCommand(K::kLoad, arg(0));
        if (l.verb == "plan") c = SessionCommand(K::kPlan);
        if (l.verb == "step") c = SessionCommand(K::kStep);
        if (l.verb == "play") c = SessionCommand(K::kPlay);
        if (l.verb == "pause") c = SessionCommand(K::kPause);
        if (l.verb == "reset") c = SessionCommand(K::kReset);
        if (l.verb == "seek") c = SessionCommand(K::kSeek, "", 0, num(0));
        if (l.verb == "joint")
          c = SessionCommand(K::kSetJoint, "", static_cast<int>(num(0)), num(1));
        if (l.verb == "grasp") {
          settings->grasp.grasp = arg(0);
          settings->grasp.method = arg(1);
          c = SessionCommand(K::kGraspRun);
        }
        if (l.verb == "grasp_step") c = SessionCommand(K::kGraspStep, "", 0, num(0));
        session->Apply(c, settings);
      }
    }
  }

 private:
  std::vector<ScriptLine> lines_;
  size_t next_ = 0;
  int wait_ = 0;
  int click_phase_ = 0;
  ImVec2 click_pos_;
  bool quit_ = false;
};

// State shared by both modes.
struct Viewer {
  Session session;
  Settings settings;
  std::vector<std::string> scenarios = ListScenarios();
  std::vector<std::string> grasps = ListGrasps();
  WidgetRects rects;
  SceneMeshCache cache;
  render::Image atlas;
  render::Overlay overlay;
  std::vector<SessionCommand> commands;

  // Panels → commands → session; returns the scene and camera of this frame.
  void UiAndUpdate(render::Scene* scene, render::Camera* camera) {
    commands.clear();
    ImGui::NewFrame();
    DrawPanels(session, scenarios, grasps, &settings, &commands, &rects);
    ImGui::Render();
    for (const SessionCommand& c : commands) {
      try {
        session.Apply(c, &settings);
      } catch (const std::exception& e) {
        session.set_status(std::string("error: ") + e.what());
      }
    }
    session.Tick(&settings);
    if (session.loaded() || (settings.grasp.active && session.grasp())) {
      *scene = BuildFrameScene(session, settings, &cache);
    } else {
      scene->grid.enabled = true;
    }
    if (!settings.camera_initialised && (session.loaded() || session.grasp())) {
      FrameOrbit(*scene, &settings.camera);
      settings.camera_initialised = true;
    }
    *camera = OrbitToCamera(settings.camera);
    ToOverlay(*ImGui::GetDrawData(), &atlas, &overlay);
  }
};

void SetUpImGui(Viewer* v, int width, int height) {
  ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  io.DisplaySize = ImVec2(static_cast<float>(width), static_cast<float>(height));
  io.DeltaTime = 1.0f / 60.0f;
  ImGui::StyleColorsLight();
  ImGui::GetStyle().WindowRounding = 4.0f;
  BuildFontAtlas(&v->atlas);
}

void PrintWidgets(const WidgetRects& rects) {
  for (const auto& [name, r] : rects.rects) {
    std::printf("widget %s %.0f %.0f %.0f %.0f\n", name.c_str(), r.x0, r.y0, r.x1, r.y1);
  }
  std::fflush(stdout);
}

int RunHeadless(const ViewerOptions& o, Viewer* v, ScriptRunner* script) {
  render::OffscreenContext context;
  render::Renderer renderer(context.proc_loader());
  SetUpImGui(v, o.width, o.height);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
  render::Image last;
  std::vector<std::string> screenshots;
  // At least two frames: ImGui settles focus and window state on the second one.
  int frame = 0;
  for (; frame < 2 || (!script->done() && !script->quit()); ++frame) {
    script->BeforeFrame(v->rects, &v->session, &v->settings, &screenshots, &io);
    render::Scene scene;
    render::Camera camera;
    v->UiAndUpdate(&scene, &camera);
    last = renderer.Render(scene, camera, o.width, o.height, {}, o.overlay ? &v->overlay : nullptr);
    for (const std::string& path : screenshots) {
      render::WritePng(path, last);
      std::printf("wrote %s\n", path.c_str());
    }
    if (frame == 1 && o.print_widgets) PrintWidgets(v->rects);
    if (frame > 100000) throw std::runtime_error("script did not finish");
  }
  if (!o.screenshot.empty()) {
    render::WritePng(o.screenshot, last);
    std::printf("wrote %s (%dx%d, %d frames)\n", o.screenshot.c_str(), o.width, o.height, frame);
  }
  ImGui::DestroyContext();
  return 0;
}

int RunWindow(const ViewerOptions& o, Viewer* v, ScriptRunner* script) {
  if (!glfwInit()) throw render::ContextError("GLFW: cannot initialise (no display?)");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_TRUE);
  GLFWwindow* window = glfwCreateWindow(o.width, o.height, "topoplan", nullptr, nullptr);
  if (window == nullptr) {
    glfwTerminate();
    throw render::ContextError("GLFW: cannot create a GL 3.3 core window");
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  int rc = 0;
  {
    render::Renderer renderer(
        [](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); });
    SetUpImGui(v, o.width, o.height);
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    ImGuiIO& io = ImGui::GetIO();
    std::vector<std::string> screenshots;
    for (int frame = 0; !glfwWindowShouldClose(window); ++frame) {
      glfwPollEvents();
      ImGui_ImplGlfw_NewFrame();
      script->BeforeFrame(v->rects, &v->session, &v->settings, &screenshots, &io);
      int fb_w = 0, fb_h = 0;
      glfwGetFramebufferSize(window, &fb_w, &fb_h);
      v->settings.width = fb_w;
      v->settings.height = fb_h;
      // Mouse: left drag orbits, right drag pans, wheel zooms (unless over a panel).
      if (!io.WantCaptureMouse) {
        if (io.MouseDown[0]) OrbitRotate(io.MouseDelta.x, io.MouseDelta.y, &v->settings.camera);
        if (io.MouseDown[1]) OrbitPan(io.MouseDelta.x, io.MouseDelta.y, fb_h, &v->settings.camera);
        if (io.MouseWheel != 0.0f) OrbitZoom(io.MouseWheel, &v->settings.camera);
      }
      render::Scene scene;
      render::Camera camera;
      v->UiAndUpdate(&scene, &camera);
      if (fb_w > 0 && fb_h > 0) {
        renderer.Draw(scene, camera, fb_w, fb_h, 0);
        renderer.DrawOverlay(v->overlay, fb_w, fb_h, 0);
      }
      // Screenshots render the same frame into an offscreen buffer of the window's size.
      for (const std::string& path : screenshots) {
        render::WritePng(path, renderer.Render(scene, camera, fb_w, fb_h, {}, &v->overlay));
        std::printf("wrote %s\n", path.c_str());
        std::fflush(stdout);
      }
      glfwSwapBuffers(window);
      if (frame == 1 && o.print_widgets) PrintWidgets(v->rects);
      if (o.exit_after > 0 && frame + 1 >= o.exit_after) break;
      if (script->quit()) break;
    }
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  glfwDestroyWindow(window);
  glfwTerminate();
  return rc;
}

}  // namespace

int RunViewer(const ViewerOptions& options) {
  Viewer v;
  v.settings.width = options.width;
  v.settings.height = options.height;
  v.settings.robot_input = options.robot_input;
  ScriptRunner script(options.script.empty() ? std::vector<ScriptLine>{}
                                             : ParseScript(options.script));
  if (!options.scenario.empty()) {
    v.session.Apply(SessionCommand(SessionCommand::Kind::kLoad, options.scenario), &v.settings);
  }
  const bool headless = options.headless || !options.screenshot.empty();
  return headless ? RunHeadless(options, &v, &script) : RunWindow(options, &v, &script);
}

}  // namespace app::ui
