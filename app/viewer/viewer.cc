#include "app/viewer/viewer.h"

#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/io.h"
#include "app/viewer/frame.h"
#include "app/viewer/imgui_overlay.h"
#include "app/viewer/panels.h"
#include "app/viewer/scene_pacer.h"
#include "app/viewer/session.h"
#include "base/assets.h"
#include "base/file_read.h"
#include "base/numbers.h"
#include "render/image.h"
#include "render/offscreen_context.h"
#include "render/overlay.h"
#include "render/renderer.h"

namespace app::ui {
namespace {

std::vector<std::string> ListGrasps() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(
           std::filesystem::path(base::AssetRoot()) / "grasps", ec)) {
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
  for (const auto& e : std::filesystem::directory_iterator(
           std::filesystem::path(base::AssetRoot()) / "scenarios", ec)) {
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// Frame times of the recent drawn frames and how many frames were drawn while the worker
// planned: what `status FILE` reports. A frame's time is the wall time from its FrameStart() to
// the next one: the whole draw-loop iteration (script, worker output, panels, scene render or
// cached image, overlay, read-back or swap).
class FrameClock {
 public:
  static constexpr size_t kKeep = 240;
  void FrameStart(bool planning) {
    const auto now = std::chrono::steady_clock::now();
    if (frames_ > 0) {
      ms_.push_back(std::chrono::duration<double, std::milli>(now - last_).count());
      planning_.push_back(last_planning_);
      if (ms_.size() > kKeep) {
        ms_.pop_front();
        planning_.pop_front();
      }
    }
    ++frames_;
    last_ = now;
    last_planning_ = planning;
    if (planning) ++while_planning_;
  }
  // The measured frames and counts (scene_renders left to the caller).
  FrameStats stats() const {
    FrameStats s;
    s.frame_ms.assign(ms_.begin(), ms_.end());
    s.frame_planning.assign(planning_.begin(), planning_.end());
    s.frames = frames_;
    s.frames_while_planning = while_planning_;
    return s;
  }

 private:
  std::deque<double> ms_;
  std::deque<bool> planning_;
  std::chrono::steady_clock::time_point last_;
  bool last_planning_ = false;
  long frames_ = 0, while_planning_ = 0;
};

// Runs `--script` lines one frame at a time: session commands immediately, `frames N` waits N
// frames, plan/step/sim_step/grasp/wait keep drawing until the worker settles and then draw one
// frame of its result before the next line (`plan async` does not wait), `click NAME` presses the
// named widget on the next frame and releases it on the one after, `screenshot PATH` saves the
// frame drawn two frames later (ImGui windows size themselves to new content one frame late).
class ScriptRunner {
 public:
  explicit ScriptRunner(std::vector<ScriptLine> lines) : lines_(std::move(lines)) {}
  bool done() const {
    return next_ >= lines_.size() && wait_ == 0 && click_phase_ == 0 && settle_ == 0 &&
           !wait_worker_;
  }
  bool quit() const { return quit_; }

  // Before ImGui::NewFrame: consumes lines up to the next wait; sets the scripted mouse.
  void BeforeFrame(const WidgetRects& rects, const FrameStats& stats, Session* session,
                   Settings* settings, std::vector<std::string>* screenshots, ImGuiIO* io) {
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
    if (settle_ > 0) {
      if (--settle_ == 0) screenshots->push_back(shot_);
      return;
    }
    if (wait_ > 0) {
      --wait_;
      return;
    }
    if (wait_worker_) {
      session->Poll(settings);
      if (!session->settled()) return;  // keep drawing while the worker runs
      wait_worker_ = false;
      // Draw the settled result once before the next line runs, as a user would see it. The
      // frame shows what the result set up (a finished grasp test rewinds to frame 0 and frames
      // the camera on it); without it, whether the next line (say `grasp_step 60`) ran before or
      // after that frame would depend on which of this Poll and the frame's own found the result.
      return;
    }
    // The first frame lays out the widgets that `click` aims at.
    if (rects.rects.empty()) return;
    while (next_ < lines_.size()) {
      const ScriptLine& l = lines_[next_++];
      try {
        if (!Run(l, rects, stats, session, settings, io)) return;
      } catch (const std::invalid_argument& e) {
        const std::string prefix = l.file + ":" + std::to_string(l.line) + ": ";
        const std::string what = e.what();
        throw std::invalid_argument(what.rfind(prefix, 0) == 0 ? what : prefix + what);
      }
    }
  }

 private:
  // Runs one line; false when the script must wait before the next one.
  bool Run(const ScriptLine& l, const WidgetRects& rects, const FrameStats& stats, Session* session,
           Settings* settings, ImGuiIO* io) {
    using K = SessionCommand::Kind;
    const auto arg = [&](size_t i) { return l.args.at(i); };
    const auto num = [&](size_t i) {  // checked by ParseScript
      return base::ParseFiniteDouble(arg(i)).value_or(0.0);
    };
    const auto apply = [&](const SessionCommand& c) { session->Apply(c, settings); };
    if (l.verb == "quit") {
      quit_ = true;
      return false;
    } else if (l.verb == "frames") {
      wait_ = std::max(0, static_cast<int>(num(0)) - 1);
      return false;
    } else if (l.verb == "screenshot") {
      shot_ = arg(0);
      settle_ = 2;
      return false;
    } else if (l.verb == "click") {
      const auto it = rects.rects.find(arg(0));
      if (it == rects.rects.end()) {
        std::vector<std::string> names;
        for (const auto& [name, r] : rects.rects) names.push_back(name);
        throw std::invalid_argument("no widget '" + arg(0) + "' on screen " + ValidChoices(names));
      }
      const WidgetRects::Rect& r = it->second;
      click_pos_ = ImVec2(0.5f * (r.x0 + r.x1), 0.5f * (r.y0 + r.y1));
      io->MousePos = click_pos_;  // hover first, press on the next frame
      click_phase_ = 1;
      return false;
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
      if (!flag)
        throw std::invalid_argument("unknown toggle '" + what + "' " +
                                    ValidChoices(ScriptToggles()));
      *flag = !*flag;
    } else if (l.verb == "planner") {
      settings->planner.planner = arg(0);
    } else if (l.verb == "seed") {
      settings->planner.seed = static_cast<unsigned>(num(0));
    } else if (l.verb == "damping") {
      settings->planner.damping = num(0);
    } else if (l.verb == "camera") {
      settings->camera.yaw_deg = static_cast<float>(num(0));
      settings->camera.pitch_deg = static_cast<float>(num(1));
      settings->camera.distance = static_cast<float>(num(2));
      if (l.args.size() == 6) {
        settings->camera.target = Eigen::Vector3f(
            static_cast<float>(num(3)), static_cast<float>(num(4)), static_cast<float>(num(5)));
      }
      settings->camera_initialised = true;
    } else if (l.verb == "status") {
      session->Poll(settings);
      WriteStatusJson(arg(0), settings->planner.planner, session->worker_status(*settings), stats);
      Note("wrote %s", arg(0).c_str());
    } else if (l.verb == "wait") {
      wait_worker_ = true;
      return false;
    } else if (l.verb == "plan") {
      apply(SessionCommand(K::kPlanAsync));
      if (!l.args.empty()) return true;  // plan async
      wait_worker_ = true;
      return false;
    } else if (l.verb == "step" || l.verb == "sim_step" || l.verb == "rrt_step" ||
               l.verb == "sim_phase") {
      const double n = l.args.empty() ? 1.0 : num(0);
      apply(SessionCommand(l.verb == "step"        ? K::kStep
                           : l.verb == "sim_step"  ? K::kSimStep
                           : l.verb == "sim_phase" ? K::kSimPhase
                                                   : K::kRrtStep,
                           "", 0, n));
      wait_worker_ = true;
      return false;
    } else if (l.verb == "cancel") {
      apply(SessionCommand(K::kCancel));
    } else if (l.verb == "move") {
      SessionCommand c(K::kMove, arg(0));
      c.position = Eigen::Vector3d(num(1), num(2), num(3));
      apply(c);
    } else if (l.verb == "grasp") {
      settings->grasp.grasp = arg(0);
      settings->grasp.method = arg(1);
      apply(SessionCommand(K::kGraspRun));
      wait_worker_ = true;
      return false;
    } else {
      SessionCommand c;
      if (l.verb == "load") c = SessionCommand(K::kLoad, arg(0));
      if (l.verb == "play") c = SessionCommand(K::kPlay);
      if (l.verb == "pause") c = SessionCommand(K::kPause);
      if (l.verb == "reset") c = SessionCommand(K::kReset);
      if (l.verb == "seek") c = SessionCommand(K::kSeek, "", 0, num(0));
      if (l.verb == "joint") c = SessionCommand(K::kSetJoint, "", static_cast<int>(num(0)), num(1));
      if (l.verb == "grasp_step") c = SessionCommand(K::kGraspStep, "", 0, num(0));
      apply(c);
    }
    return true;
  }

  std::vector<ScriptLine> lines_;
  size_t next_ = 0;
  int wait_ = 0;
  int click_phase_ = 0;
  int settle_ = 0;
  std::string shot_;
  bool wait_worker_ = false;
  ImVec2 click_pos_;
  bool quit_ = false;
};

// The RRT/BiRRT trees as they grow: edges parent → node as lines, each node's grasp point as a
// small cross (tree 0 from the start in blue, tree 1 from the goal in orange).
void AddRrtTrees(const std::vector<RrtTreeView>& trees, render::Scene* scene) {
  static const std::array<float, 4> kColours[] = {{0.10f, 0.35f, 0.85f, 1.0f},
                                                  {0.90f, 0.45f, 0.05f, 1.0f}};
  for (size_t i = 0; i < trees.size(); ++i) {
    render::Lines edges, nodes;
    edges.strip = nodes.strip = false;
    edges.rgba = nodes.rgba = kColours[std::min<size_t>(i, 1)];
    nodes.width = 2.0f;
    const float h = 0.006f;  // cross half-size [m]
    for (size_t k = 0; k < trees[i].points.size(); ++k) {
      const Eigen::Vector3f p = trees[i].points[k].cast<float>();
      if (trees[i].parents[k] >= 0) {
        edges.points.push_back(trees[i].points[trees[i].parents[k]].cast<float>());
        edges.points.push_back(p);
      }
      for (int a = 0; a < 3; ++a) {
        nodes.points.push_back(p - h * Eigen::Vector3f::Unit(a));
        nodes.points.push_back(p + h * Eigen::Vector3f::Unit(a));
      }
    }
    if (!edges.points.empty()) scene->lines.push_back(std::move(edges));
    if (!nodes.points.empty()) scene->lines.push_back(std::move(nodes));
  }
}

// State shared by both modes.
struct Viewer {
  Session session;
  Settings settings;
  std::vector<std::string> scenarios = ListScenarios();
  std::vector<std::string> grasps = ListGrasps();
  WidgetRects rects;
  visualize::SceneMeshCache cache;
  render::Image atlas;
  render::Overlay overlay;
  std::vector<SessionCommand> commands;
  std::vector<SessionCommand> pending;  // from mouse input, applied with the panels' commands
  Eigen::Vector3d drag_sent = Eigen::Vector3d::Zero();  // object position of the last drag move
  FrameClock clock;
  ScenePacer pacer;
  bool worker_computing = false;  // in this frame (plan, step, re-plan or simulation)
  const std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();

  // What `status` reports.
  FrameStats stats() const {
    FrameStats s = clock.stats();
    s.scene_renders = pacer.renders();
    return s;
  }

  // Renders `scene` into the renderer's cached image when the pacer says it is due (always when
  // `force`d); true when it did.
  bool CacheSceneIfDue(const render::Scene& scene, const render::Camera& camera, int width,
                       int height, bool force, render::Renderer* renderer) {
    const std::uint64_t content = SceneHash(scene), view = ViewHash(camera, width, height);
    const double now =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    if (!pacer.Due(content, view, worker_computing, force, now)) return false;
    renderer->CacheScene(scene, camera, width, height);
    pacer.Rendered(content, view, now);
    return true;
  }

  // Worker output → session; panels → commands → session; returns the scene and camera of this
  // frame.
  void UiAndUpdate(render::Scene* scene, render::Camera* camera) {
    commands.clear();
    session.Poll(&settings);
    const WorkerStatus w = session.worker_status(settings);
    clock.FrameStart(w.computing && w.job != "grasp");
    worker_computing = w.computing;
    ImGui::NewFrame();
    DrawPanels(session, scenarios, grasps, &settings, &commands, &rects);
    ImGui::Render();
    commands.insert(commands.end(), pending.begin(), pending.end());
    pending.clear();
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
      if (!settings.grasp.active) AddRrtTrees(session.rrt_trees(), scene);
    } else {
      *scene = render::Scene();
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

// Shift + left drag moves settings.move.object (default: the scenario's first object) in the view
// plane. While it is dragged the session moves it and re-plans (SessionCommand::kMove, receding
// horizon from the executed slice) whenever the worker is idle and the object went at least
// kDragReplanStep farther; on release once more at the final position.
constexpr double kDragReplanStep = 0.01;  // m
void DragObject(const ImGuiIO& io, int viewport_height, Viewer* v) {
  MoveSettings& m = v->settings.move;
  const planning::Scenario* s = v->session.scenario();
  if (s == nullptr || s->spec.objects.empty()) return;
  const planning::ObjectSpec* object = &s->spec.objects.front();
  for (const planning::ObjectSpec& o : s->spec.objects) {
    if (o.name == m.object) object = &o;
  }
  if (io.MouseDown[0] && !m.dragging) {
    m.dragging = true;
    m.object = object->name;
    m.start = v->drag_sent = object->xyz;
    m.offset.setZero();
  }
  if (io.MouseDown[0]) {
    const OrbitCamera& c = v->settings.camera;
    const double yaw = c.yaw_deg * M_PI / 180.0, pitch = c.pitch_deg * M_PI / 180.0;
    const Eigen::Vector3d to_eye(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                                 std::sin(pitch));
    const Eigen::Vector3d right = Eigen::Vector3d::UnitZ().cross(to_eye).normalized();
    const Eigen::Vector3d up = to_eye.cross(right);
    const double metres_per_pixel =
        2.0 * c.distance * std::tan(0.5 * c.fovy_deg * M_PI / 180.0) / std::max(1, viewport_height);
    m.offset += metres_per_pixel * (-io.MouseDelta.x * right + io.MouseDelta.y * up);
    char text[128];
    std::snprintf(text, sizeof text, "moving %s to (%.3f, %.3f, %.3f): release to re-plan",
                  m.object.c_str(), m.start.x() + m.offset.x(), m.start.y() + m.offset.y(),
                  m.start.z() + m.offset.z());
    v->session.set_status(text);
    const Eigen::Vector3d at = m.start + m.offset;
    if (!v->session.busy() && (at - v->drag_sent).norm() >= kDragReplanStep) {
      SessionCommand c(SessionCommand::Kind::kMove, m.object);
      c.position = v->drag_sent = at;
      v->pending.push_back(c);
    }
  } else if (m.dragging) {
    m.dragging = false;
    SessionCommand c(SessionCommand::Kind::kMove, m.object);
    c.position = m.start + m.offset;
    v->pending.push_back(c);
  }
}

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
  const render::Overlay* overlay = o.overlay ? &v->overlay : nullptr;
  render::Image last;
  render::Scene scene;
  render::Camera camera;
  std::vector<std::string> screenshots;
  // At least two frames: ImGui settles focus and window state on the second one.
  // The final screenshot waits two frames after the script's end, like `screenshot`.
  int frame = 0, settle = 2;
  for (; frame < 2 || (!script->done() && !script->quit()) || settle-- > 0; ++frame) {
    script->BeforeFrame(v->rects, v->stats(), &v->session, &v->settings, &screenshots, &io);
    v->UiAndUpdate(&scene, &camera);
    // The scene is rendered again only when it changed (screenshots: always); every frame
    // composes the cached image with the panels and reads it back, as a window would present it.
    v->CacheSceneIfDue(scene, camera, o.width, o.height, !screenshots.empty(), &renderer);
    last = renderer.ReadCachedScene(overlay);
    for (const std::string& path : screenshots) {
      render::WritePng(path, last);
      Note("wrote %s", path.c_str());
    }
    if (frame == 1 && o.print_widgets) PrintWidgets(v->rects);
    if (frame > 100000) throw std::runtime_error("script did not finish");
  }
  if (!o.screenshot.empty()) {
    v->CacheSceneIfDue(scene, camera, o.width, o.height, /*force=*/true, &renderer);
    last = renderer.ReadCachedScene(overlay);
    render::WritePng(o.screenshot, last);
    Note("wrote %s (%dx%d, %d frames)", o.screenshot.c_str(), o.width, o.height, frame);
  }
  ImGui::DestroyContext();
  return 0;
}

int RunWindow(const ViewerOptions& o, Viewer* v, ScriptRunner* script) {
  if (!glfwInit()) {
    const char* display = std::getenv("DISPLAY");
    throw render::ContextError(
        std::string("no window can be opened (GLFW could not start; DISPLAY is ") +
        (display && *display ? std::string("'") + display + "'" : std::string("not set")) +
        "). Without a display: `topoplan view ... --screenshot out.png` draws one frame "
        "headless, `--script FILE` runs a script headless; or run the window under "
        "`xvfb-run -a topoplan view ...`");
  }
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
      script->BeforeFrame(v->rects, v->stats(), &v->session, &v->settings, &screenshots, &io);
      int fb_w = 0, fb_h = 0;
      glfwGetFramebufferSize(window, &fb_w, &fb_h);
      v->settings.width = fb_w;
      v->settings.height = fb_h;
      // Mouse: left drag orbits, right drag pans, wheel zooms (unless over a panel); Shift + left
      // drag moves an object.
      if (!io.WantCaptureMouse && (io.KeyShift || v->settings.move.dragging)) {
        DragObject(io, fb_h, v);
      } else if (!io.WantCaptureMouse) {
        if (io.MouseDown[0]) OrbitRotate(io.MouseDelta.x, io.MouseDelta.y, &v->settings.camera);
        if (io.MouseDown[1]) OrbitPan(io.MouseDelta.x, io.MouseDelta.y, fb_h, &v->settings.camera);
        if (io.MouseWheel != 0.0f) OrbitZoom(io.MouseWheel, &v->settings.camera);
      }
      render::Scene scene;
      render::Camera camera;
      v->UiAndUpdate(&scene, &camera);
      if (fb_w > 0 && fb_h > 0) {
        v->CacheSceneIfDue(scene, camera, fb_w, fb_h, false, &renderer);
        renderer.DrawCachedScene(0);
        renderer.DrawOverlay(v->overlay, fb_w, fb_h, 0);
      }
      // Screenshots render the same frame into an offscreen buffer of the window's size.
      for (const std::string& path : screenshots) {
        render::WritePng(path, renderer.Render(scene, camera, fb_w, fb_h, {}, &v->overlay));
        Note("wrote %s", path.c_str());
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
  if (!(options.preview_interval_ms >= 0.0 && options.preview_interval_ms <= 1e6)) {
    throw std::invalid_argument("--preview-interval: expected milliseconds in [0, 1e6]");
  }
  Viewer v;
  v.pacer = ScenePacer(options.preview_interval_ms / 1000.0);
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
