#include "egl_context.hpp"

#include <EGL/eglext.h>
#include <GL/gl.h>

#include <cstdio>
#include <cstring>
#include <mutex>

#include "mjarm/error.hpp"

namespace mjarm::render_detail {
namespace {

const char* const kDriverHint =
    "; headless rendering needs an EGL driver: install Debian's libegl-mesa0 and libgl1-mesa-dri "
    "(scripts/setup.sh does)";

std::string egl_error_text(EGLint code) {
  switch (code) {
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
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    default: {
      char text[32];
      std::snprintf(text, sizeof text, "EGL error 0x%04x", static_cast<unsigned>(code));
      return text;
    }
  }
}

[[noreturn]] void fail(const char* call) {
  throw Error(std::string("offscreen rendering: ") + call + " failed (" +
              egl_error_text(eglGetError()) + ")" + kDriverHint);
}

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const std::size_t n = std::strlen(name);
  for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + n, name)) {
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  }
  return false;
}

// One EGL display for the whole process. eglTerminate on a display invalidates every context
// made on it, so it is terminated only when the last context is gone (a reference count), which
// lets a second renderer live after, or beside, the first.
std::mutex display_mutex;
EGLDisplay shared_display = EGL_NO_DISPLAY;
int display_users = 0;

EGLDisplay open_display() {
  // Mesa's surfaceless platform needs neither X11 nor Wayland nor a GPU; asking for it by name
  // (instead of via the EGL_PLATFORM variable) leaves the environment alone.
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (get_platform_display != nullptr) {
      EGLDisplay display =
          get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (display != EGL_NO_DISPLAY) return display;
    }
  }
  return eglGetDisplay(EGL_DEFAULT_DISPLAY);
}

EGLDisplay acquire_display() {
  std::lock_guard lock(display_mutex);
  if (display_users == 0) {
    EGLDisplay display = open_display();
    if (display == EGL_NO_DISPLAY) fail("eglGetDisplay");
    EGLint major = 0, minor = 0;
    if (eglInitialize(display, &major, &minor) != EGL_TRUE) fail("eglInitialize");
    shared_display = display;
  }
  ++display_users;
  return shared_display;
}

void release_display() noexcept {
  std::lock_guard lock(display_mutex);
  if (--display_users == 0) {
    eglTerminate(shared_display);
    // frees EGL's per-thread state of this thread (reallocated on the next use)
    eglReleaseThread();
    shared_display = EGL_NO_DISPLAY;
  }
}

}  // namespace

EglContext::EglContext() : display_(acquire_display()) {
  try {
    // MuJoCo's classic renderer draws with the compatibility profile of desktop OpenGL into its own FBO
    const EGLint attributes[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                 EGL_OPENGL_BIT,   EGL_RED_SIZE,    8,
                                 EGL_GREEN_SIZE,   8,               EGL_BLUE_SIZE,
                                 8,                EGL_ALPHA_SIZE,  8,
                                 EGL_DEPTH_SIZE,   24,              EGL_STENCIL_SIZE,
                                 8,                EGL_NONE};
    EGLConfig config = nullptr;
    EGLint count = 0;
    if (eglChooseConfig(display_, attributes, &config, 1, &count) != EGL_TRUE)
      fail("eglChooseConfig");
    if (count < 1) {
      throw Error(
          "offscreen rendering: the EGL driver offers no RGBA8 + depth24/stencil8 OpenGL "
          "configuration" +
          std::string(kDriverHint));
    }
    if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) fail("eglBindAPI(EGL_OPENGL_API)");
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, nullptr);
    if (context_ == EGL_NO_CONTEXT) fail("eglCreateContext");
    Scope current(*this);
    auto text = [](GLenum name) {
      const auto* s = reinterpret_cast<const char*>(glGetString(name));
      return std::string(s != nullptr ? s : "?");
    };
    description_ = text(GL_VENDOR) + " " + text(GL_RENDERER) + ", OpenGL " + text(GL_VERSION);
  } catch (...) {
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
    release_display();
    throw;
  }
}

EglContext::~EglContext() {
  if (eglGetCurrentContext() == context_) release();
  eglDestroyContext(display_, context_);
  release_display();
}

void EglContext::make_current() {
  if (eglGetCurrentContext() == context_) return;
  if (eglBindAPI(EGL_OPENGL_API) != EGL_TRUE) fail("eglBindAPI(EGL_OPENGL_API)");
  if (eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_) != EGL_TRUE)
    fail("eglMakeCurrent (surfaceless)");
}

EglContext::Scope::Scope(EglContext& context)
    : context_(context),
      display_(eglGetCurrentDisplay()),
      draw_(eglGetCurrentSurface(EGL_DRAW)),
      read_(eglGetCurrentSurface(EGL_READ)),
      previous_(eglGetCurrentContext()) {
  context_.make_current();
}

EglContext::Scope::~Scope() {
  if (previous_ == context_.context_) return;  // it was already current: leave it so
  if (previous_ == EGL_NO_CONTEXT || eglMakeCurrent(display_, draw_, read_, previous_) != EGL_TRUE)
    context_.release();
}

void EglContext::release() noexcept {
  if (eglGetCurrentContext() != EGL_NO_CONTEXT)
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

}  // namespace mjarm::render_detail
