// What one frame of the viewer (window or headless) shows: scene and camera from a Session and
// its Settings. Both modes call these, so a scripted headless run reproduces the window.
#pragma once

#include "visualize/scene_builder.h"
#include "app/viewer/session.h"
#include "app/viewer/settings.h"
#include "render/scene.h"

namespace app {

// Robot at session.ShownQ(settings) with the objects, chains (settings.view.chains), collision
// or visual geometry, the scenario's box task regions (AddTaskBoxes), and the ground grid. Meshes
// are converted once into `cache`.
render::Scene BuildFrameScene(const Session& session, const Settings& settings,
                              visualize::SceneMeshCache* cache);

// The orbit camera as a render::Camera: eye = target + distance·(cos p cos y, cos p sin y, sin p)
// with yaw y and pitch p in degrees, up = +z.
render::Camera OrbitToCamera(const OrbitCamera& orbit);

// Sets `orbit` to frame every shape of `scene` (target at the scene's centre, distance to fit).
void FrameOrbit(const render::Scene& scene, OrbitCamera* orbit);

// Mouse interaction in pixels: orbit (yaw/pitch), pan (move the target in the view plane) and
// zoom (scale the distance by 0.9^clicks). Pitch stays within ±89°.
void OrbitRotate(float dx_pixels, float dy_pixels, OrbitCamera* orbit);
void OrbitPan(float dx_pixels, float dy_pixels, int viewport_height, OrbitCamera* orbit);
void OrbitZoom(float wheel_clicks, OrbitCamera* orbit);

}  // namespace app
