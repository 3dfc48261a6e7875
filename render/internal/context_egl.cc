// EGL surfaceless backend of OffscreenContext (EGL_MESA_platform_surfaceless, no window system,
// no pbuffer): a GL 3.3 core context made current with EGL_NO_SURFACE. GL entry points come from
// eglGetProcAddress (Mesa returns core functions too).
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <string>

#include "render/internal/context_impl.h"

namespace render::internal {
namespace {

std::string EglErrorText(const char* what) {
  char code[32];
  std::snprintf(code, sizeof(code), "0x%04x", static_cast<unsigned>(eglGetError()));
  return std::string("EGL surfaceless: ") + what + " failed (error " + code + ")";
}

class EglContext final : public OffscreenContext::Impl {
 public:
  EglContext() {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display == nullptr) {
      throw ContextError("EGL surfaceless: eglGetPlatformDisplayEXT missing (no Mesa EGL?)");
    }
    display_ = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display_ == EGL_NO_DISPLAY) throw ContextError(EglErrorText("eglGetPlatformDisplayEXT"));
    EGLint major = 0, minor = 0;
    if (!eglInitialize(display_, &major, &minor)) {
      throw ContextError(EglErrorText("eglInitialize"));
    }
    if (!eglBindAPI(EGL_OPENGL_API)) {
      eglTerminate(display_);
      throw ContextError(EglErrorText("eglBindAPI(OpenGL)"));
    }
    // EGL_SURFACE_TYPE must be given: the default (WINDOW_BIT) matches nothing here.
    const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                     EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint num_configs = 0;
    if (!eglChooseConfig(display_, config_attribs, &config, 1, &num_configs) || num_configs < 1) {
      eglTerminate(display_);
      throw ContextError(EglErrorText("eglChooseConfig"));
    }
    const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      3,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attribs);
    if (context_ == EGL_NO_CONTEXT) {
      eglTerminate(display_);
      throw ContextError(EglErrorText("eglCreateContext(3.3 core)"));
    }
    MakeCurrent();
  }
  ~EglContext() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
    eglTerminate(display_);
  }

  void MakeCurrent() override {
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      throw ContextError(EglErrorText("eglMakeCurrent"));
    }
  }
  void* Load(const char* name) override { return reinterpret_cast<void*>(eglGetProcAddress(name)); }
  GlBackend backend() const override { return GlBackend::kEgl; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<OffscreenContext::Impl> CreateEglContext() {
  return std::make_unique<EglContext>();
}

}  // namespace render::internal
