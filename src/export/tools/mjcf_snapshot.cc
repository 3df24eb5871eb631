// mjcf_snapshot: loads an MJCF file with MuJoCo, optionally simulates it, and saves what MuJoCo's
// own renderer draws as a PNG, so docs/export.md can show an export loaded in its simulator.
// Usage: prs_mjcf_snapshot SCENE.xml OUT.png [SECONDS] (0 by default: the scene as exported).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <mujoco/mujoco.h>
#include <png.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

// A desktop-GL context without a window or a display: Mesa's surfaceless EGL platform (MuJoCo
// 2.2 draws with the fixed-function pipeline, so not GLES).
void MakeOffscreenContext() {
  EGLDisplay display =
      eglGetPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  const EGLint attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                               EGL_OPENGL_BIT,   EGL_DEPTH_SIZE,  24,
                               EGL_NONE};
  EGLConfig config = nullptr;
  EGLint count = 0;
  if (!eglInitialize(display, nullptr, nullptr) ||
      !eglChooseConfig(display, attributes, &config, 1, &count) || count < 1 ||
      !eglBindAPI(EGL_OPENGL_API)) {
    throw std::runtime_error("no EGL display with desktop OpenGL (is Mesa's EGL installed?)");
  }
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, nullptr);
  if (context == EGL_NO_CONTEXT ||
      !eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    throw std::runtime_error("cannot create an EGL OpenGL context");
  }
}

void WritePng(const std::string& path, const std::vector<unsigned char>& rgb, int width,
              int height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = width;
  image.height = height;
  image.format = PNG_FORMAT_RGB;
  // OpenGL rows run bottom-up; a negative stride flips them.
  if (!png_image_write_to_file(&image, path.c_str(), 0, rgb.data(), -3 * width, nullptr))
    throw std::runtime_error("cannot write " + path + ": " + image.message);
}

// MuJoCo's free camera frames the whole model (lookat its centre, distance from its extent);
// seen from ahead (+y) and above.
mjvCamera MakeOverviewCamera(const mjModel* m) {
  mjvCamera camera;
  mjv_defaultFreeCamera(m, &camera);
  camera.distance *= 0.8;
  camera.azimuth = -75;
  camera.elevation = -28;
  return camera;
}

void Render(const mjModel* m, mjData* d, const std::string& out) {
  MakeOffscreenContext();
  mjvScene scene;
  mjvOption option;
  mjrContext context;
  mjv_defaultScene(&scene);
  mjv_defaultOption(&option);
  mjr_defaultContext(&context);
  mjv_makeScene(m, &scene, 2000);
  mjr_makeContext(m, &context, mjFONTSCALE_100);
  mjr_setBuffer(mjFB_OFFSCREEN, &context);
  const mjrRect viewport = mjr_maxViewport(&context);
  mjvCamera camera = MakeOverviewCamera(m);
  mjv_updateScene(m, d, &option, nullptr, &camera, mjCAT_ALL, &scene);
  mjr_render(viewport, &scene, &context);
  std::vector<unsigned char> rgb(3 * viewport.width * viewport.height);
  mjr_readPixels(rgb.data(), nullptr, viewport, &context);
  WritePng(out, rgb, viewport.width, viewport.height);
  mjr_freeContext(&context);
  mjv_freeScene(&scene);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || argc > 4) {
    std::fprintf(stderr, "usage: %s SCENE.xml OUT.png [SECONDS]\n", argv[0]);
    return 2;
  }
  char error[1000] = "";
  mjModel* m = mj_loadXML(argv[1], nullptr, error, sizeof error);
  if (m == nullptr) {
    std::fprintf(stderr, "%s: MuJoCo cannot load %s: %s\n", argv[0], argv[1], error);
    return 1;
  }
  mjData* d = mj_makeData(m);
  const double seconds = argc == 4 ? std::atof(argv[3]) : 0;
  while (d->time < seconds) mj_step(m, d);
  mj_forward(m, d);
  try {
    Render(m, d, argv[2]);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
  std::printf("%s: %d bodies, t = %.2f s -> %s\n", argv[1], m->nbody - 1, d->time, argv[2]);
  mj_deleteData(d);
  mj_deleteModel(m);
  return 0;
}
