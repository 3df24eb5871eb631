// EGL set-up for offscreen rendering: a desktop-GL context (compatibility profile, as MuJoCo
// 2.x draws with the fixed pipeline) on one of the two displays Mesa offers a process, the
// software device (EGL_MESA_device_software) and the surfaceless platform, taken in turn
// while both draw with llvmpipe.
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

PFNEGLGETPLATFORMDISPLAYEXTPROC GetDisplayFunction() {
  auto get_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!get_display) FailEgl("eglGetProcAddress(eglGetPlatformDisplayEXT)");
  return get_display;
}

// Whether the current context draws with llvmpipe (its GL_RENDERER), as the software device's
// always does: Mesa's surfaceless platform takes a GPU's driver where one is installed, whose
// pictures would differ.
bool DrawsWithLlvmpipe() {
  using GetString = const unsigned char* (*)(unsigned);
  auto get_string = reinterpret_cast<GetString>(eglGetProcAddress("glGetString"));
  constexpr unsigned kGlRenderer = 0x1F01;
  const unsigned char* renderer = get_string ? get_string(kGlRenderer) : nullptr;
  return renderer && std::strncmp(reinterpret_cast<const char*>(renderer), "llvmpipe", 8) == 0;
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
  const bool take_second = contexts_made.fetch_add(1) % 2 == 1;
  const PFNEGLGETPLATFORMDISPLAYEXTPROC get_display = GetDisplayFunction();
  const EGLDisplay software = OpenSoftwareDeviceDisplay(get_display);
  if (take_second || software == EGL_NO_DISPLAY) {
    const EGLDisplay surfaceless =
        get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (surfaceless != EGL_NO_DISPLAY) {
      if (software == EGL_NO_DISPLAY) {
        Open(surfaceless);
        return;
      }
      // The second display only where it works and draws what the first does; otherwise every
      // context on the software device.
      try {
        Open(surfaceless);
        if (DrawsWithLlvmpipe()) return;
      } catch (const std::runtime_error&) {
      }
      Close();
    }
  }
  if (software == EGL_NO_DISPLAY) FailEgl("eglGetPlatformDisplayEXT");
  Open(software);
}

void EglContext::Open(void* display) {
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

void EglContext::Close() {
  if (display_ == nullptr) return;
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  if (surface_) eglDestroySurface(display_, surface_);
  if (context_) eglDestroyContext(display_, context_);
  display_ = context_ = surface_ = nullptr;
  // No eglTerminate: the display is process-wide (a later EglContext gets the same one), and
  // terminating it unloads Mesa's driver, orphaning a few of its allocations (LeakSanitizer
  // then fails the ASan tests).
}

EglContext::~EglContext() { Close(); }

void EglContext::MakeCurrent() const {
  if (!eglMakeCurrent(display_, surface_, surface_, context_)) FailEgl("eglMakeCurrent");
}

void EglContext::Release() const {
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace prs::render::internal
