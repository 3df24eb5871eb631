// A headless OpenGL context from EGL on Mesa's software rasteriser (llvmpipe): no GPU, no X
// display, no window. Internal to src/render; docs/render.md says why EGL and not OSMesa.
#pragma once

namespace prs::render::internal {

/// Owns an EGL display and a desktop-OpenGL context, current on the creating thread. The
/// context has no window surface: MuJoCo draws into its own offscreen framebuffer.
///
/// Contexts alternate between two displays: llvmpipe has one rasterizer per display, which
/// draws one picture at a time for all the display's contexts, and Mesa gives a process at most
/// two (its software device and its surfaceless platform). The k-th context of the process
/// takes display k mod 2, so that two threads, each with a context of its own, draw at once.
/// The surfaceless platform serves only while it draws with llvmpipe too (on a machine with a
/// GPU's Mesa driver it takes that driver, whose pixels differ): otherwise, and where either
/// display is missing, every context takes the one display.
class EglContext {
 public:
  /// Throws std::runtime_error naming the failed EGL step and its error code.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Makes the context current on the calling thread again.
  void MakeCurrent() const;
  /// Makes no context current on the calling thread, so that another thread can take this one.
  void Release() const;

  /// The EGL display (an EGLDisplay), for telling two contexts' displays apart.
  const void* display() const { return display_; }

  /// Current on the calling thread for one scope, released at its end (for objects that move
  /// between threads, such as a controller's renderer in a pool).
  class Scope {
   public:
    explicit Scope(const EglContext& egl) : egl_(egl) { egl_.MakeCurrent(); }
    ~Scope() { egl_.Release(); }
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    const EglContext& egl_;
  };

 private:
  void Open(void* display);  // makes the context on `display`, current on this thread
  void Close();              // undoes Open

  void* display_ = nullptr;
  void* context_ = nullptr;
  void* surface_ = nullptr;  // a 1x1 pbuffer only when surfaceless contexts are refused
};

}  // namespace prs::render::internal
