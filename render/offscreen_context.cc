// OffscreenContext: backend selection and the public wrapper (backends in render/internal/).
#include "render/offscreen_context.h"

#include <cstdlib>
#include <stdexcept>

#include "render/internal/context_impl.h"

namespace render {

GlBackend ParseGlBackend(const std::string& text, const std::string& what) {
  if (text == "osmesa") return GlBackend::kOsmesa;
  if (text == "egl") return GlBackend::kEgl;
  throw std::invalid_argument(what + ": unknown GL backend '" + text +
                              "' (expected osmesa or egl)");
}

GlBackend ResolveGlBackend(GlBackend requested) {
  if (requested != GlBackend::kAuto) return requested;
  const char* env = std::getenv("TOPOPLAN_GL");
  if (env == nullptr || *env == '\0') return GlBackend::kOsmesa;
  try {
    return ParseGlBackend(env, "TOPOPLAN_GL");
  } catch (const std::invalid_argument& e) {
    throw ContextError(e.what());
  }
}

const char* GlBackendName(GlBackend backend) {
  switch (backend) {
    case GlBackend::kOsmesa:
      return "osmesa";
    case GlBackend::kEgl:
      return "egl";
    case GlBackend::kAuto:
      break;
  }
  return "auto";
}

OffscreenContext::OffscreenContext(GlBackend backend) {
  switch (ResolveGlBackend(backend)) {
    case GlBackend::kEgl:
      impl_ = internal::CreateEglContext();
      break;
    default:
      impl_ = internal::CreateOsmesaContext();
      break;
  }
}

OffscreenContext::~OffscreenContext() = default;

void OffscreenContext::MakeCurrent() { impl_->MakeCurrent(); }

GlBackend OffscreenContext::backend() const { return impl_->backend(); }

GlProcLoader OffscreenContext::proc_loader() const {
  Impl* impl = impl_.get();
  return [impl](const char* name) { return impl->Load(name); };
}

}  // namespace render
