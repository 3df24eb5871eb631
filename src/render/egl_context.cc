// EGL set-up for offscreen rendering: a desktop-GL context (compatibility profile, as MuJoCo
// 2.x draws with the fixed pipeline) on one of the two displays Mesa offers a process, the
// software device (EGL_MESA_device_software) and the surfaceless platform, taken in turn.
#include "render/egl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <atomic>
#include <cstring>
#include <stdexcept>
#include <string>

namespace prs::render::internal {
namespace {

[[noreturn]] void FailEgl(const std::string& step) {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04x", static_cast<unsigned>(eglGetError()));
  throw std::runtime_error("cannot create the offscreen OpenGL context: " + step +
                           " failed (EGL error " + code +
                           "); is Mesa's EGL installed (libegl-mesa0, libgl1-mesa-dri)?");
}

bool HasExtension(const char* extensions, const char* name) {
  if (extensions == nullptr) return false;
  const size_t length = std::strlen(name);
  for (const char* at = std::strstr(extensions, name); at; at = std::strstr(at + 1, name)) {
    const bool starts = at == extensions || at[-1] == ' ';
    const bool ends = at[length] == '\0' || at[length] == ' ';
    if (starts && ends) return true;
  }
  return false;
}

// The software device, so that pixels are the same on every machine (a GPU would differ).
EGLDisplay OpenSoftwareDeviceDisplay(PFNEGLGETPLATFORMDISPLAYEXTPROC get_display) {
  auto query_devices =
      reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto query_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
      eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (!query_devices || !query_string) return EGL_NO_DISPLAY;
  EGLDeviceEXT devices[16];
  EGLint count = 0;
  if (!query_devices(16, devices, &count)) return EGL_NO_DISPLAY;
  for (EGLint i = 0; i < count; ++i) {
    if (HasExtension(query_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
      return get_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
  }
  return EGL_NO_DISPLAY;
}

EGLDisplay OpenSurfacelessDisplay(PFNEGLGETPLATFORMDISPLAYEXTPROC get_display) {
  return get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
}

// Display `k mod 2` of the two above, or the other one when that one is missing.
EGLDisplay OpenDisplay(int k) {
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) FailEgl("eglGetProcAddress(eglGetPlatformDisplayEXT)");
  EGLDisplay display =
      k % 2 == 0 ? OpenSoftwareDeviceDisplay(get_display) : OpenSurfacelessDisplay(get_display);
  if (display == EGL_NO_DISPLAY)
    display =
        k % 2 == 0 ? OpenSurfacelessDisplay(get_display) : OpenSoftwareDeviceDisplay(get_display);
  if (display == EGL_NO_DISPLAY) FailEgl("eglGetPlatformDisplayEXT");
  return display;
}

EGLConfig ChooseConfig(EGLDisplay display) {
  // Attribute, value pairs.
  // clang-format off
  const EGLint attributes[] = {
      EGL_SURFACE_TYPE, EGL_PBUFFER_BIT,    // MuJoCo draws into its own framebuffer object
      EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT,  // desktop OpenGL, not GLES
      EGL_RED_SIZE, 8, EGL_GREEN_SIZE, 8, EGL_BLUE_SIZE, 8, EGL_DEPTH_SIZE, 24,
      EGL_NONE};
  // clang-format on
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglChooseConfig(display, attributes, &config, 1, &count) || count < 1)
    FailEgl("eglChooseConfig");
  return config;
}

}  // namespace

EglContext::EglContext() {
  static std::atomic<int> contexts_made{0};
  EGLDisplay display = OpenDisplay(contexts_made.fetch_add(1));
  if (!eglInitialize(display, nullptr, nullptr)) FailEgl("eglInitialize");
  display_ = display;
  if (!eglBindAPI(EGL_OPENGL_API)) FailEgl("eglBindAPI(EGL_OPENGL_API)");
  const EGLConfig config = ChooseConfig(display);
  context_ = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context_ == EGL_NO_CONTEXT) FailEgl("eglCreateContext");
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
    const EGLint size[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
    surface_ = eglCreatePbufferSurface(display, config, size);
    if (surface_ == EGL_NO_SURFACE) FailEgl("eglCreatePbufferSurface");
  }
  MakeCurrent();
}

EglContext::~EglContext() {
  if (display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (surface_) eglDestroySurface(display_, surface_);
  if (context_) eglDestroyContext(display_, context_);
  // No eglTerminate: the display is process-wide (a later EglContext gets the same one), and
  // terminating it unloads Mesa's driver, orphaning a few of its allocations (LeakSanitizer
  // then fails the ASan tests).
}

void EglContext::MakeCurrent() const {
  if (!eglMakeCurrent(display_, surface_, surface_, context_)) FailEgl("eglMakeCurrent");
}

void EglContext::Release() const {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace prs::render::internal
