// An OpenGL 4.5 core context without a window, through EGL.
//
// The display comes from EGL_EXT_platform_device (every EGL device is enumerated,
// hardware devices first: what NVIDIA's driver offers headless) or from
// EGL_MESA_platform_surfaceless (Mesa: a GPU's driver, or llvmpipe on machines
// without one). Rendering goes to framebuffer objects, so no surface is needed.
#pragma once

#include <memory>
#include <string>

namespace bw::render {

class GlContext {
 public:
  // Creates the context and makes it current on the calling thread: on EGL device
  // `device` when it is >= 0 (InputError when there is no such device), otherwise on
  // the first display that works, in the order above. Throws RunError (exit code 1)
  // saying what was looked for when no display offers OpenGL 4.5 core.
  static std::unique_ptr<GlContext> create(int device = -1);
  ~GlContext();
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)".
  const std::string& renderer() const;
  const std::string& version() const;
  // How the display was found, e.g. "EGL device 0" or "EGL surfaceless platform".
  const std::string& display() const;

  struct Impl;

 private:
  explicit GlContext(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace bw::render
