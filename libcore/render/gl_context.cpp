#include "render/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <vector>

#include "common/error.h"
#include "render/gl_api.h"

namespace bw::render {

struct GlContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  EGLSurface surface = EGL_NO_SURFACE;
  std::string renderer, version, how;

  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface != EGL_NO_SURFACE) eglDestroySurface(display, surface);
    if (context != EGL_NO_CONTEXT) eglDestroyContext(display, context);
    eglTerminate(display);
  }
};

namespace {

bool has_extension(const char* list, const char* name) {
  if (!list) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

void* lookup(const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

std::string egl_error_name(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return fmt::format("EGL error 0x{:x}", e);
  }
}

// Tries to make a 4.5 core context on `display`; on success fills `impl` and returns
// an empty string, otherwise the reason.
std::string try_display(EGLDisplay display, GlContext::Impl& impl) {
  if (display == EGL_NO_DISPLAY) return "no display";
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) return "eglInitialize failed: " + egl_error_name(eglGetError());
  auto give_up = [&](const std::string& why) {
    eglTerminate(display);
    return why;
  };
  if (!eglBindAPI(EGL_OPENGL_API)) return give_up("no desktop OpenGL API");
  const char* ext = eglQueryString(display, EGL_EXTENSIONS);
  EGLConfig config = EGL_NO_CONFIG_KHR;
  const bool configless = has_extension(ext, "EGL_KHR_no_config_context") || has_extension(ext, "EGL_MESA_configless_context");
  const bool surfaceless = has_extension(ext, "EGL_KHR_surfaceless_context");
  if (!configless || !surfaceless) {
    const EGLint want[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, want, &config, 1, &count) || count < 1)
      return give_up("no EGL config for OpenGL with pbuffers");
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               4,
                               EGL_CONTEXT_MINOR_VERSION,
                               5,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK,
                               EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                               EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT)
    return give_up("no OpenGL 4.5 core context (" + egl_error_name(eglGetError()) + ")");
  EGLSurface surface = EGL_NO_SURFACE;
  if (!surfaceless) {
    const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface = eglCreatePbufferSurface(display, config, size);
  }
  if (!eglMakeCurrent(display, surface, surface, context)) {
    eglDestroyContext(display, context);
    return give_up("eglMakeCurrent failed: " + egl_error_name(eglGetError()));
  }
  if (const char* missing = gl::load_functions(lookup)) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    return give_up(std::string("OpenGL function ") + missing + " is missing");
  }
  GLint gl_major = 0, gl_minor = 0;
  gl::GetIntegerv(GL_MAJOR_VERSION, &gl_major);
  gl::GetIntegerv(GL_MINOR_VERSION, &gl_minor);
  if (gl_major * 10 + gl_minor < 45) {
    eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display, context);
    return give_up(fmt::format("OpenGL {}.{}, not 4.5", gl_major, gl_minor));
  }
  impl.display = display;
  impl.context = context;
  impl.surface = surface;
  auto str = [](GLenum name) {
    const GLubyte* s = gl::GetString(name);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  impl.renderer = str(GL_RENDERER);
  impl.version = str(GL_VERSION);
  return {};
}

}  // namespace

std::unique_ptr<GlContext> GlContext::create(int device) {
  auto impl = std::make_unique<Impl>();
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  std::vector<std::string> tried;
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));

  // 1. EGL devices: hardware first, software (Mesa's llvmpipe device) last.
  std::vector<std::pair<EGLDeviceEXT, int>> software;
  if (get_platform_display && has_extension(client, "EGL_EXT_platform_device") &&
      has_extension(client, "EGL_EXT_device_enumeration")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLint count = 0;
    // More devices than any machine has; the driver fills at most this many.
    constexpr EGLint kMaxDevices = 32;
    EGLDeviceEXT devices[kMaxDevices];
    if (query_devices && query_devices(kMaxDevices, devices, &count)) {
      if (device >= 0) {  // this device and no other
        if (device >= count) fail_input("--device {}: there is no such EGL device ({} found)", device, count);
        const std::string why =
            try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[device], nullptr), *impl);
        if (!why.empty()) fail_run("EGL device {} offers no OpenGL 4.5 core context: {}", device, why);
        impl->how = fmt::format("EGL device {}", device);
        return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
      }
      for (EGLint i = 0; i < count; ++i) {
        const char* ext = query_string ? query_string(devices[i], EGL_EXTENSIONS) : nullptr;
        if (has_extension(ext, "EGL_MESA_device_software")) {
          software.emplace_back(devices[i], i);
          continue;
        }
        const std::string why = try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr), *impl);
        if (why.empty()) {
          impl->how = fmt::format("EGL device {}", i);
          return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
        }
        tried.push_back(fmt::format("EGL device {}: {}", i, why));
      }
    } else {
      tried.push_back("EGL_EXT_platform_device: no devices");
    }
  } else {
    tried.push_back("EGL_EXT_platform_device: not offered");
  }
  if (device >= 0) fail_input("--device {}: no EGL devices to choose from ({})", device, tried.back());

  // 2. Mesa's surfaceless platform.
  if (get_platform_display && has_extension(client, "EGL_MESA_platform_surfaceless")) {
    const std::string why =
        try_display(get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr), *impl);
    if (why.empty()) {
      impl->how = "EGL surfaceless platform";
      return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
    }
    tried.push_back("EGL_MESA_platform_surfaceless: " + why);
  } else {
    tried.push_back("EGL_MESA_platform_surfaceless: not offered");
  }

  // 3. Software devices.
  for (const auto& [soft, index] : software) {
    const std::string why = try_display(get_platform_display(EGL_PLATFORM_DEVICE_EXT, soft, nullptr), *impl);
    if (why.empty()) {
      impl->how = fmt::format("EGL device {} (software)", index);
      return std::unique_ptr<GlContext>(new GlContext(std::move(impl)));
    }
    tried.push_back(fmt::format("EGL device {} (software): {}", index, why));
  }

  std::string list;
  for (const std::string& t : tried) list += (list.empty() ? "" : "; ") + t;
  fail_run("no EGL display with OpenGL 4.5 core (looked for EGL_EXT_platform_device and "
           "EGL_MESA_platform_surfaceless: {})",
           list);
}

GlContext::GlContext(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
GlContext::~GlContext() = default;

const std::string& GlContext::renderer() const { return impl_->renderer; }
const std::string& GlContext::version() const { return impl_->version; }
const std::string& GlContext::display() const { return impl_->how; }

}  // namespace bw::render
