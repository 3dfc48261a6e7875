// Backend interface behind render::OffscreenContext (one implementation per file).
#pragma once

#include <memory>

#include "render/offscreen_context.h"

namespace render {

class OffscreenContext::Impl {
 public:
  virtual ~Impl() = default;
  virtual void MakeCurrent() = 0;
  // GetProcAddress of this backend (valid while the context is current).
  virtual void* Load(const char* name) = 0;
  virtual GlBackend backend() const = 0;
};

namespace internal {
// Each throws ContextError with the reason on failure; the context is current on return.
std::unique_ptr<OffscreenContext::Impl> CreateOsmesaContext();
std::unique_ptr<OffscreenContext::Impl> CreateEglContext();
}  // namespace internal

}  // namespace render
