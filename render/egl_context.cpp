#include "render/egl_context.h"

#define GL_GLEXT_PROTOTYPES
#include <EGL/eglext.h>
#include <GL/gl.h>

#include <cstdio>
#include <cstring>
#include <vector>

namespace cascade::render {

namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name))
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

template <typename F>
F egl_function(const char* name) {
  return reinterpret_cast<F>(eglGetProcAddress(name));
}

std::string egl_error(const char* call) {
  char text[96];
  std::snprintf(text, sizeof text, "%s failed (EGL error 0x%04x)", call, unsigned(eglGetError()));
  return text;
}

// An initialised display on an NVIDIA device, or EGL_NO_DISPLAY. NVIDIA's devices carry
// EGL_NV_device_cuda; Mesa's software device (EGL_MESA_device_software) is left to the
// surfaceless platform.
EGLDisplay nvidia_device_display(const char* client_extensions) {
  if (!has_extension(client_extensions, "EGL_EXT_device_enumeration") ||
      !has_extension(client_extensions, "EGL_EXT_platform_device"))
    return EGL_NO_DISPLAY;
  auto query_devices = egl_function<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
  auto query_device_string = egl_function<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
  auto get_platform_display = egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!query_devices || !query_device_string || !get_platform_display) return EGL_NO_DISPLAY;
  EGLint count = 0;
  if (!query_devices(0, nullptr, &count) || count <= 0) return EGL_NO_DISPLAY;
  std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
  if (!query_devices(count, devices.data(), &count)) return EGL_NO_DISPLAY;
  for (EGLint i = 0; i < count; ++i) {
    if (!has_extension(query_device_string(devices[std::size_t(i)], EGL_EXTENSIONS), "EGL_NV_device_cuda")) continue;
    EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[std::size_t(i)], nullptr);
    if (display != EGL_NO_DISPLAY && eglInitialize(display, nullptr, nullptr)) return display;
  }
  return EGL_NO_DISPLAY;
}

EGLDisplay surfaceless_display(const char* client_extensions) {
  if (!has_extension(client_extensions, "EGL_MESA_platform_surfaceless"))
    throw RenderError("EGL: no NVIDIA device and no EGL_MESA_platform_surfaceless (install libegl-mesa0 and "
                      "libgl1-mesa-dri)");
  auto get_platform_display = egl_function<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
  if (!get_platform_display) throw RenderError("EGL: eglGetPlatformDisplayEXT is missing");
  EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (display == EGL_NO_DISPLAY) throw RenderError(egl_error("eglGetPlatformDisplayEXT(surfaceless)"));
  if (!eglInitialize(display, nullptr, nullptr)) throw RenderError(egl_error("eglInitialize(surfaceless)"));
  return display;
}

}  // namespace

EglContext::EglContext() {
  const char* client_extensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  display_ = nvidia_device_display(client_extensions);
  platform_ = "device";
  if (display_ == EGL_NO_DISPLAY) {
    display_ = surfaceless_display(client_extensions);
    platform_ = "surfaceless";
  }
  if (!has_extension(eglQueryString(display_, EGL_EXTENSIONS), "EGL_KHR_surfaceless_context"))
    throw RenderError("EGL: the " + platform_ + " display lacks EGL_KHR_surfaceless_context");
  if (!eglBindAPI(EGL_OPENGL_API)) throw RenderError(egl_error("eglBindAPI(EGL_OPENGL_API)"));
  // EGL_SURFACE_TYPE defaults to EGL_WINDOW_BIT, which neither platform offers; pbuffer configs
  // exist on both (the context draws into framebuffer objects and never uses the surface type).
  const EGLint config_attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,
                                      EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  if (!eglChooseConfig(display_, config_attributes, &config, 1, &configs) || configs < 1)
    throw RenderError(egl_error("eglChooseConfig(OpenGL)"));
  const EGLint context_attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 3,
                                       EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                       EGL_NONE};
  context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, context_attributes);
  if (context_ == EGL_NO_CONTEXT) throw RenderError(egl_error("eglCreateContext(OpenGL 3.3 core)"));
  if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
    eglDestroyContext(display_, context_);
    throw RenderError(egl_error("eglMakeCurrent"));
  }
}

// The display is not terminated: EGL displays are shared by the whole process, and terminating
// one would pull it from under any other renderer's context.
EglContext::~EglContext() {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglReleaseThread();
}

std::string EglContext::renderer() const { return reinterpret_cast<const char*>(glGetString(GL_RENDERER)); }
std::string EglContext::version() const { return reinterpret_cast<const char*>(glGetString(GL_VERSION)); }

}  // namespace cascade::render
