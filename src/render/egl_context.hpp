#pragma once
// A headless OpenGL context made with EGL (private to the render room: the public headers never
// include EGL). No window, no display server, no GPU needed: on Mesa the surfaceless platform
// renders with the llvmpipe software rasteriser when no GPU is present.

#include <EGL/egl.h>

#include <string>

namespace mjarm::render_detail {

/// One desktop-OpenGL (compatibility profile) context without any surface. MuJoCo renders into
/// its own framebuffer object, so no pbuffer or window is needed.
///
/// Contexts are bound to a thread only while in use (a `Scope` around the GL work), so several
/// contexts live side by side and each renderer may be driven from whichever thread calls it
/// (one thread at a time). The EGL display is shared by every context
/// of the process and terminated when the last context goes.
class EglContext {
 public:
  /// Creates the context.
  /// @throws Error naming the EGL call that failed and the Debian packages that provide a driver.
  EglContext();
  ~EglContext();
  EglContext(const EglContext&) = delete;
  EglContext& operator=(const EglContext&) = delete;

  /// Makes this context current on the calling thread.
  /// @throws Error when EGL refuses (e.g. the context is current on another thread).
  void make_current();
  /// Unbinds whatever context is current on the calling thread (no-op when none).
  void release() noexcept;

  /// Makes the context current for one scope and, on every exit path, restores whatever EGL
  /// context was current on the thread before (or none), so a caller's own EGL context survives.
  class Scope {
   public:
    explicit Scope(EglContext& context);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    EglContext& context_;
    EGLDisplay display_;
    EGLSurface draw_;
    EGLSurface read_;
    EGLContext previous_;
  };

  /// "vendor renderer, version" of the OpenGL implementation (valid after construction).
  const std::string& description() const noexcept { return description_; }

 private:
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string description_;
};

}  // namespace mjarm::render_detail
