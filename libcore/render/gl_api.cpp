#include "render/gl_api.h"

namespace bw::render::gl {

#define BW_GL_DEFINE(type, name) type name = nullptr;
BW_GL_FUNCTIONS(BW_GL_DEFINE)
#undef BW_GL_DEFINE

const char* load_functions(void* (*lookup)(const char* name)) {
#define BW_GL_LOAD(type, name)                                   \
  name = reinterpret_cast<type>(lookup("gl" #name));             \
  if (!name) return "gl" #name;
  BW_GL_FUNCTIONS(BW_GL_LOAD)
#undef BW_GL_LOAD
  return nullptr;
}

}  // namespace bw::render::gl
