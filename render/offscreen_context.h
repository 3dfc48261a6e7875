// Headless OpenGL contexts for the CLI and the tests.
//
// Two backends, both Mesa llvmpipe on Debian 12 (and byte-identical in output, measured):
//   kOsmesa  OSMesa (libOSMesa), the default. Mesa >= 25.1 no longer ships it.
//   kEgl     EGL with the surfaceless platform (EGL_MESA_platform_surfaceless).
// The backend is chosen by the constructor argument, or for kAuto by the environment variable
// TOPOPLAN_GL=osmesa|egl (unset: osmesa). OSMesa code lives in exactly one file
// (render/internal/context_osmesa.cc), EGL code in context_egl.cc.
//
// GL entry points are never called through linked gl* symbols: the Renderer loads a function
// table through proc_loader() (OSMesaGetProcAddress / eglGetProcAddress). That way libOSMesa and
// libGL (GLFW window in the same binary) can coexist, since both export gl* symbols.
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include "base/errors.h"

namespace render {

// Something the machine lacks rather than bad input: no GL context, a missing system font. The
// CLI maps it (and ContextError) to exit code 3 (environment error).
using base::EnvironmentError;

// No usable GL context (library missing, context creation failed, GL too old).
class ContextError : public EnvironmentError {
 public:
  using EnvironmentError::EnvironmentError;
};

// Looks a GL entry point up by name in the *current* context's implementation; returns null when
// unknown. What OSMesaGetProcAddress, eglGetProcAddress and glfwGetProcAddress provide.
using GlProcLoader = std::function<void*(const char* name)>;

enum class GlBackend { kAuto, kOsmesa, kEgl };

// Parses "osmesa" / "egl" (case-sensitive) into a backend; throws std::invalid_argument naming
// `what` otherwise.
GlBackend ParseGlBackend(const std::string& text, const std::string& what);

// Backend kAuto resolves to: $TOPOPLAN_GL if set ("osmesa" or "egl"; anything else throws
// ContextError), else kOsmesa.
GlBackend ResolveGlBackend(GlBackend requested);
const char* GlBackendName(GlBackend backend);

// An OpenGL 3.3 core (or newer) context with no window, current on the creating thread after
// construction. Drawing goes into framebuffer objects (the Renderer makes its own), never into a
// default framebuffer. Not copyable; one per thread at a time.
class OffscreenContext {
 public:
  // Creates and makes current a context. Throws ContextError with the reason when the backend's
  // library or a 3.3 core context is not available.
  explicit OffscreenContext(GlBackend backend = GlBackend::kAuto);
  ~OffscreenContext();
  OffscreenContext(const OffscreenContext&) = delete;
  OffscreenContext& operator=(const OffscreenContext&) = delete;

  // Makes this context current on the calling thread.
  void MakeCurrent();
  // The backend actually in use (never kAuto).
  GlBackend backend() const;
  // Entry-point loader for this context; pass it to Renderer.
  GlProcLoader proc_loader() const;

  // Implementation interface (render/internal/context_*.cc); not for callers.
  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace render
