#pragma once
// The GLFW shell of the interactive viewer (private to src/teleop): the window, MuJoCo's
// rendering resources, event routing and drawing (viewer_shell.cpp), the loop and the script
// runner (viewer.cpp). What it drives is a `ViewerDriver` (viewer_driver.hpp).

#include <mujoco/mujoco.h>

#include <exception>
#include <memory>
#include <string>

#include "mjarm/render/image.hpp"
#include "mjarm/teleop/viewer.hpp"
#include "viewer_driver.hpp"
#include "viewer_overlay.hpp"
#include "viewer_ui.hpp"

struct GLFWwindow;

namespace mjarm::detail {

/// glfwInit / glfwTerminate for the lifetime of the object.
class GlfwLibrary {
 public:
  GlfwLibrary();
  ~GlfwLibrary();
  GlfwLibrary(const GlfwLibrary&) = delete;
  GlfwLibrary& operator=(const GlfwLibrary&) = delete;
};

struct WindowDeleter {
  void operator()(GLFWwindow* window) const noexcept;
};

class ViewerShell {
 public:
  /// The viewer of `run_viewer`: one arm or several hands, as @p options say.
  ViewerShell(const Robot& robot, const ViewerOptions& options);
  /// A window driven by @p driver (the passive viewer's), titled @p title.
  ViewerShell(std::unique_ptr<ViewerDriver> driver, const ViewerOptions& options,
              const std::string& title);
  ~ViewerShell();
  ViewerShell(const ViewerShell&) = delete;
  ViewerShell& operator=(const ViewerShell&) = delete;

  ViewerReport run();  // viewer.cpp
  /// On an error: the driver keeps what it recorded.
  void save() noexcept { driver_->save(); }

 private:
  // viewer_shell.cpp: OpenGL resources and drawing
  void make_gl();
  void free_gl() noexcept;
  void render(Image* capture);
  void changed();  // after the driver changed: a new model, period or panel values
  // viewer_shell.cpp: events (real and synthetic share `on_event`)
  static void install_callbacks(GLFWwindow* window);
  void read_window_input();
  void on_event();
  void on_key(int key, bool shift);
  void on_panel(PanelAction action);
  void reset();
  void press(int button, double x, double y, bool control = false);
  void on_view_press();  // a selection, or the start of a perturbation
  void release(double x, double y);
  void move_to(double x, double y);
  // runs an event handler from a GLFW callback: an exception must not unwind through GLFW's C
  // code, so it is kept and rethrown by the loop after glfwPollEvents
  template <class F>
  void guarded(F&& handler) noexcept {
    if (failure_) return;
    try {
      handler();
    } catch (...) {
      failure_ = std::current_exception();
    }
  }
  // viewer.cpp: scripts
  void run_script();
  void execute(const ScriptCommand& command);
  void screenshot(const std::string& path);

  ViewerOptions options_;
  std::unique_ptr<ViewerDriver> driver_;
  ViewerUi& ui_;
  GlfwLibrary glfw_;
  std::unique_ptr<GLFWwindow, WindowDeleter> window_;
  double buffer_to_window_ = 1.0;
  std::string gl_;
  mjvScene scene_{};
  mjvCamera camera_{};
  mjvOption vis_{};
  mjrContext con_{};
  mjvPerturb pert_{};  // the selected body and the mouse's drag on it (perturbing drivers)
  const mjModel* gl_model_ = nullptr;  // the model the context and scene were made for

  ViewerSchedule schedule_;
  RateMeter fps_;
  RateMeter speed_;
  OverlayInfo info_;
  OverlayText overlay_;
  OverlayText overlay_right_;
  bool refresh_panel_ = false;  // the panel's values changed in code: redraw it
  bool paused_ = false;
  bool quit_ = false;
  std::string ended_by_;
  double clock_ = 0.0;  // time of the current loop iteration (virtual when scripted) [s]
  std::int64_t frames_ = 0;
  std::size_t next_command_ = 0;
  std::int64_t wait_until_ = 0;
  ViewerReport report_;
  std::exception_ptr failure_;  // from an event handler run by a GLFW callback
};

}  // namespace mjarm::detail
