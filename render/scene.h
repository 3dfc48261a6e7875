// render::Scene: the plain description of one 3-D frame that the Renderer draws (the project's
// mjvScene). It knows nothing of robots, planners or topology: app/scene_builder turns planning
// state into these shapes, app/scene_json reads them from a file.
//
// Frames and units: one right-handed world frame, z up by convention, lengths in metres (any unit
// works as long as camera and shapes agree). Colours are linear 0..1 RGBA floats that the renderer
// writes as 8-bit sRGB-ish values without gamma conversion (what you specify is what you get on a
// flat, fully lit surface facing the key light).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace render {

// Surface appearance. rgba[3] < 1 makes the shape translucent (drawn after opaque shapes, sorted
// back to front by shape centre).
struct Material {
  std::array<float, 4> rgba{0.8f, 0.8f, 0.8f, 1.0f};
  float specular = 0.25f;   // strength of the Blinn-Phong highlight, 0..1
  float shininess = 32.0f;  // Blinn-Phong exponent
};

// An indexed triangle mesh in its own frame. `normals` is either empty (the renderer computes
// flat-ish area-weighted vertex normals) or has one unit normal per vertex. Triangles are
// counter-clockwise seen from outside. Meshes are shared between frames through shared_ptr so the
// renderer can upload each one once (it caches GPU buffers per TriangleMesh object). render reads
// no mesh files: the caller fills this (the app converts the meshes its loader read).
struct TriangleMesh {
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3f> normals;
  std::vector<std::uint32_t> indices;  // 3 per triangle, each < positions.size()
};

// One solid. world_from_shape is a rigid transform (4x4, last row 0 0 0 1) placing the shape's
// own frame; the `size` meaning depends on kind, all in the shape frame:
//   kSphere   centre at origin; size.x() = radius
//   kCapsule  axis along +z from z = -size.y()/2 to +size.y()/2 (segment length), radius size.x()
//   kCylinder same axis and length as the capsule, flat caps, radius size.x()
//   kBox      centred at origin, full edge lengths size.x(), size.y(), size.z()
//   kMesh     `mesh` scaled component-wise by size (use (1,1,1) for none)
struct Shape {
  enum class Kind { kSphere, kCapsule, kCylinder, kBox, kMesh };
  Kind kind = Kind::kSphere;
  Eigen::Matrix4f world_from_shape = Eigen::Matrix4f::Identity();
  Eigen::Vector3f size = Eigen::Vector3f::Ones();
  std::shared_ptr<const TriangleMesh> mesh;  // kMesh only
  Material material;
};

// A chain drawn as a tube: a cylinder of `radius` along each segment p_i -> p_{i+1} plus a sphere
// ("bead") of radius bead_radius (radius if <= 0) at every point. `segment_colors` is empty (all
// segments use `material`) or holds one RGBA per segment (N-1 entries for N points), e.g. to colour
// a chain by its writhe contribution. Beads take the colour of the segment that starts at them
// (the last bead that of the last segment).
struct Tube {
  std::vector<Eigen::Vector3f> points;
  float radius = 0.01f;
  float bead_radius = 0.0f;
  Material material;
  std::vector<std::array<float, 4>> segment_colors;
};

// Thin lines (GL lines, `width` pixels wide; no lighting): segments p_0-p_1, p_2-p_3, ... when
// `strip` is false, a connected polyline when true. For axes, rays, debug geometry.
struct Lines {
  std::vector<Eigen::Vector3f> points;
  bool strip = true;
  float width = 1.0f;
  std::array<float, 4> rgba{0, 0, 0, 1};
};

// A square ground grid in the plane z = height, centred at (center.x, center.y), `extent` metres
// on a side, a line every `spacing` metres (every 5th line darker).
struct Grid {
  bool enabled = false;
  Eigen::Vector2f center = Eigen::Vector2f::Zero();
  float height = 0.0f;
  float extent = 4.0f;
  float spacing = 0.25f;
  std::array<float, 4> plane_rgba{0.93f, 0.93f, 0.93f, 1.0f};
  std::array<float, 4> line_rgba{0.70f, 0.70f, 0.70f, 1.0f};
};

// A directional light: light travels along -direction (direction points from the scene towards
// the light, world frame, need not be unit). At most 4 lights are used.
struct Light {
  Eigen::Vector3f direction{0.4f, 0.3f, 1.0f};
  std::array<float, 3> rgb{0.8f, 0.8f, 0.8f};
};

// Everything drawn in one frame. When `lights` is empty the renderer uses a default rig (a key
// light over the camera's right shoulder, a dimmer fill light, and hemispheric ambient).
struct Scene {
  std::vector<Shape> shapes;
  std::vector<Tube> tubes;
  std::vector<Lines> lines;
  Grid grid;
  std::vector<Light> lights;
  std::array<float, 3> ambient{0.25f, 0.25f, 0.27f};
  std::array<float, 3> background{1.0f, 1.0f, 1.0f};
};

// A pinhole camera looking from `eye` at `target`; `up` is projected to be the image's up
// direction (defaults to +z, must not be parallel to target - eye). fovy_deg is the full vertical
// field of view in degrees, (0, 180). Near/far clip distances <= 0 are chosen from the scene
// bounds. The image is width x height pixels with square pixels; a camera-frame point
// (x right, y up, z towards the viewer) projects to pixel column u = W/2 + f x/(-z),
// row v = H/2 - f y/(-z) (rows top-down, pixel centres at +0.5), f = (H/2)/tan(fovy/2).
struct Camera {
  Eigen::Vector3f eye{3.0f, -3.0f, 2.0f};
  Eigen::Vector3f target{0.0f, 0.0f, 0.5f};
  Eigen::Vector3f up{0.0f, 0.0f, 1.0f};
  float fovy_deg = 45.0f;
  float near_clip = 0.0f;
  float far_clip = 0.0f;
};

// Convenience constructors for shapes (world-frame placement).
Shape MakeSphere(const Eigen::Vector3f& center, float radius, const Material& material);
// A capsule or cylinder from point a to point b (a != b).
Shape MakeCapsule(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                  const Material& material);
Shape MakeCylinder(const Eigen::Vector3f& a, const Eigen::Vector3f& b, float radius,
                   const Material& material);
// An axis-aligned box (then rotated by `rotation`) centred at `center` with full edge lengths.
Shape MakeBox(const Eigen::Vector3f& center, const Eigen::Vector3f& edge_lengths,
              const Material& material,
              const Eigen::Matrix3f& rotation = Eigen::Matrix3f::Identity());

// Material from an sRGB 0..1 colour triple (alpha 1).
Material MakeMaterial(float r, float g, float b, float a = 1.0f);

}  // namespace render
