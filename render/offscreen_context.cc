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

namespace {

// Mesa reads GALLIUM_DRIVER when the context is made; a name it does not know crashes OSMesa's
// context creation (seen with "GALLIUM_DRIVER=nonsense"). Only the software drivers a headless
// machine has are accepted; anything else is an environment error naming the variable.
void CheckGalliumDriver() {
  const char* driver = std::getenv("GALLIUM_DRIVER");
  if (driver == nullptr || *driver == '\0') return;
  const std::string d = driver;
  if (d == "llvmpipe" || d == "softpipe") return;
  std::string shown;
  for (char c : d.substr(0, 40)) shown += (static_cast<unsigned char>(c) < 0x20) ? '?' : c;
  throw ContextError("GALLIUM_DRIVER='" + shown +
                     "' is not a driver topoplan can render with (llvmpipe or softpipe; unset it "
                     "for the default)");
}

}  // namespace

OffscreenContext::OffscreenContext(GlBackend backend) {
  CheckGalliumDriver();
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
