// An OpenGL 3.3 core context with no window and no display server. It uses the EGL device platform
// when an NVIDIA device is present (the one that works on NVIDIA servers) and otherwise Mesa's
// surfaceless platform (llvmpipe on a machine without a GPU). Drawing goes into framebuffer
// objects: the context has no default surface.
//
// The context is current on the thread that constructs it, and only that thread may render with
// it or destroy it: a service gives the renderer a thread of its own.
#pragma once

#include <EGL/egl.h>

#include <stdexcept>
#include <string>

namespace cascade::render {

class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class EglContext {
 public:
  EglContext();  // throws RenderError with what failed
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  // "device" or "surfaceless".
  const std::string& platform() const { return platform_; }
  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6".
  std::string renderer() const;
  std::string version() const;

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string platform_;
};

}  // namespace cascade::render
