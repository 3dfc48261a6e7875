// Loading the GL function table (see gl_api.h).
#include "render/internal/gl_api.h"

#include <string>

namespace render::internal {

void LoadGlApi(const GlProcLoader& load, GlApi* gl) {
  if (!load) throw ContextError("GL: no entry-point loader given");
#define TOPOPLAN_GL_LOAD(type, name)                                            \
  gl->name = reinterpret_cast<type>(load("gl" #name));                          \
  if (gl->name == nullptr) {                                                    \
    throw ContextError(std::string("GL: entry point gl") + #name + " missing"); \
  }
  TOPOPLAN_GL_FUNCTIONS(TOPOPLAN_GL_LOAD)
#undef TOPOPLAN_GL_LOAD
}

}  // namespace render::internal
