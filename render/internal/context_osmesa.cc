// OSMesa backend of OffscreenContext: the only file in the project that includes GL/osmesa.h.
// The context is 3.3 core (Mesa gives 4.5 core, llvmpipe). It is made current on a tiny client
// buffer that is never drawn into: the renderer always draws into its own framebuffer objects,
// which give the same pixels on every backend (OSMesa's default framebuffer does not).
#include <GL/osmesa.h>

#include <string>
#include <vector>

#include "render/internal/context_impl.h"

namespace render::internal {
namespace {

constexpr int kBufferSize = 4;  // pixels per side of the unused default framebuffer

class OsmesaContext final : public OffscreenContext::Impl {
 public:
  OsmesaContext() : buffer_(4 * kBufferSize * kBufferSize, 0) {
    const int attribs[] = {OSMESA_FORMAT,
                           OSMESA_RGBA,
                           OSMESA_DEPTH_BITS,
                           24,
                           OSMESA_STENCIL_BITS,
                           8,
                           OSMESA_PROFILE,
                           OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION,
                           3,
                           OSMESA_CONTEXT_MINOR_VERSION,
                           3,
                           0};
    context_ = OSMesaCreateContextAttribs(attribs, nullptr);
    if (context_ == nullptr) {
      throw ContextError(
          "OSMesa: could not create a GL 3.3 core context (is libosmesa6 installed? try "
          "TOPOPLAN_GL=egl)");
    }
    MakeCurrent();
  }
  ~OsmesaContext() override { OSMesaDestroyContext(context_); }

  void MakeCurrent() override {
    if (!OSMesaMakeCurrent(context_, buffer_.data(), GL_UNSIGNED_BYTE, kBufferSize, kBufferSize)) {
      throw ContextError("OSMesa: OSMesaMakeCurrent failed");
    }
  }
  void* Load(const char* name) override {
    return reinterpret_cast<void*>(OSMesaGetProcAddress(name));
  }
  GlBackend backend() const override { return GlBackend::kOsmesa; }

 private:
  OSMesaContext context_ = nullptr;
  std::vector<unsigned char> buffer_;
};

}  // namespace

std::unique_ptr<OffscreenContext::Impl> CreateOsmesaContext() {
  return std::make_unique<OsmesaContext>();
}

}  // namespace render::internal
