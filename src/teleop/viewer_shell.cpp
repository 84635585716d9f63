// The viewer's window: GLFW set-up, MuJoCo's rendering resources, drawing and event routing.
#include "viewer_shell.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <utility>

#include "mjarm/error.hpp"

namespace mjarm::detail {

namespace {

std::string g_glfw_error;  // the last GLFW error (GLFW reports through a C callback)

void record_glfw_error(int code, const char* description) {
  g_glfw_error = std::string(description != nullptr ? description : "unknown error") +
                 " (GLFW error " + std::to_string(code) + ")";
}

ViewerShell* shell_of(GLFWwindow* window) {
  return static_cast<ViewerShell*>(glfwGetWindowUserPointer(window));
}

constexpr int kMaxGeoms = 4000;  // scene capacity: the bundled scenes use a few hundred

}  // namespace

GlfwLibrary::GlfwLibrary() {
  glfwSetErrorCallback(record_glfw_error);
  if (glfwInit() != GLFW_TRUE) {
    throw Error("cannot initialise GLFW on display '" +
                std::string(std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "") +
                "': " + g_glfw_error + "; " + kNoDisplayMessage);
  }
}

GlfwLibrary::~GlfwLibrary() { glfwTerminate(); }

void WindowDeleter::operator()(GLFWwindow* window) const noexcept { glfwDestroyWindow(window); }

ViewerShell::ViewerShell(const Robot& robot, const ViewerOptions& options)
    : ViewerShell(options.several_hands ? make_teleop_driver(robot, options)
                                        : make_arm_driver(robot, options),
                  options, "mjarm view: " + robot.name()) {}

ViewerShell::ViewerShell(std::unique_ptr<ViewerDriver> driver, const ViewerOptions& options,
                         const std::string& title)
    : options_(options),
      driver_(std::move(driver)),
      ui_(driver_->ui()),
      schedule_(options.rates, driver_->control_period(), 0.0) {
  if (options.width < 320 || options.height < 240) {
    throw Error("viewer: the window must be at least 320×240 pixels, got " +
                std::to_string(options.width) + "×" + std::to_string(options.height));
  }
  // multisampling when the display offers it (Xvfb may not)
  for (const int samples : {4, 0}) {
    glfwWindowHint(GLFW_SAMPLES, samples);
    window_.reset(glfwCreateWindow(options.width, options.height, title.c_str(), nullptr, nullptr));
    if (window_) break;
  }
  if (!window_) throw Error("viewer: cannot open a window: " + g_glfw_error);
  glfwMakeContextCurrent(window_.get());
  glfwSwapInterval(0);  // the schedule paces frames, not the display's refresh
  glfwSetWindowUserPointer(window_.get(), this);
  int window_width = 0, buffer_width = 0, height = 0;
  glfwGetWindowSize(window_.get(), &window_width, &height);
  glfwGetFramebufferSize(window_.get(), &buffer_width, &height);
  buffer_to_window_ = window_width > 0 ? static_cast<double>(buffer_width) / window_width : 1.0;

  // the GL description, looked up through GLFW so that no GL library is linked for it
  using GetString = const unsigned char* (*)(unsigned int);
  if (auto get = reinterpret_cast<GetString>(glfwGetProcAddress("glGetString"))) {
    for (const unsigned int name : {0x1F00u, 0x1F01u, 0x1F02u}) {  // vendor, renderer, version
      const unsigned char* text = get(name);
      if (text != nullptr)
        gl_ += (gl_.empty() ? "" : ", ") + std::string(reinterpret_cast<const char*>(text));
    }
  }

  mjv_defaultOption(&vis_);
  mjv_defaultPerturb(&pert_);
  mjv_defaultScene(&scene_);
  mjr_defaultContext(&con_);
  driver_->initial_camera(camera_);
  make_gl();
  install_callbacks(window_.get());
}

ViewerShell::~ViewerShell() {
  if (window_) glfwMakeContextCurrent(window_.get());
  free_gl();
}

void ViewerShell::make_gl() {
  const mjModel& m = driver_->robot().model();
  mjv_makeScene(&m, &scene_, kMaxGeoms);
  mjr_makeContext(&m, &con_, mjFONTSCALE_100);
  gl_model_ = &m;
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_.get(), &width, &height);
  ui_.layout(width, height);
  ui_.attach(con_);
  // a first scene, so that camera moves before the first frame have a camera to move
  mjv_updateScene(&m, &driver_->data(), &vis_, nullptr, &camera_, mjCAT_ALL, &scene_);
}

void ViewerShell::free_gl() noexcept {
  if (gl_model_ == nullptr) return;
  mjr_freeContext(&con_);
  mjv_freeScene(&scene_);
  mjr_defaultContext(&con_);
  mjv_defaultScene(&scene_);
  gl_model_ = nullptr;
}

// after the driver changed something: rendering resources for a new model, the control period,
// the panel redrawn at the next frame
void ViewerShell::changed() {
  if (&driver_->robot().model() != gl_model_) {
    free_gl();
    make_gl();
  }
  schedule_.set_control_period(driver_->control_period());
  refresh_panel_ = true;
}

void ViewerShell::render(Image* capture) {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_.get(), &width, &height);
  const mjrRect& window = ui_.input().rect[rect_window];
  if (width != window.width || height != window.height) ui_.layout(width, height);
  if (refresh_panel_) {
    ui_.refresh(con_);
    refresh_panel_ = false;
  }
  mjData& d = driver_->data();
  const mjModel& m = driver_->robot().model();
  mjv_updateScene(&m, &d, &vis_, driver_->perturbs() ? &pert_ : nullptr, &camera_, mjCAT_ALL,
                  &scene_);
  driver_->add_markers(scene_);

  mjr_setBuffer(mjFB_WINDOW, &con_);
  const mjrRect view = ui_.view();
  mjr_render(view, &scene_, &con_);
  info_.paused = paused_;
  info_.fps = fps_.rate();
  info_.speed = speed_.rate();
  info_.note = driver_->note;
  driver_->overlay(info_, overlay_, overlay_right_);
  mjr_overlay(mjFONT_NORMAL, mjGRID_TOPLEFT, view, overlay_.labels.c_str(), overlay_.values.c_str(),
              &con_);
  if (!overlay_right_.labels.empty()) {
    mjr_overlay(mjFONT_NORMAL, mjGRID_TOPRIGHT, view, overlay_right_.labels.c_str(),
                overlay_right_.values.c_str(), &con_);
  }
  mjr_overlay(mjFONT_NORMAL, mjGRID_BOTTOMLEFT, view, driver_->help(), nullptr, &con_);
  if (paused_) mjr_overlay(mjFONT_BIG, mjGRID_BOTTOMRIGHT, view, "Paused", nullptr, &con_);
  driver_->draw(view, con_);
  mjui_render(&ui_.ui(), &ui_.input(), &con_);

  if (capture != nullptr) {
    // the back buffer before the swap; OpenGL rows run bottom-up
    Image bottom_up(width, height);
    mjr_readPixels(bottom_up.rgb.data(), nullptr, mjrRect{0, 0, width, height}, &con_);
    *capture = Image(width, height);
    const std::size_t row = static_cast<std::size_t>(width) * 3;
    for (int y = 0; y < height; ++y) {
      std::copy_n(bottom_up.rgb.data() + static_cast<std::size_t>(height - 1 - y) * row, row,
                  capture->rgb.data() + static_cast<std::size_t>(y) * row);
    }
  }
  glfwSwapBuffers(window_.get());
  ++frames_;
}

// ---- events ----

void ViewerShell::install_callbacks(GLFWwindow* window) {
  glfwSetKeyCallback(window, [](GLFWwindow* w, int key, int, int act, int) {
    if (act == GLFW_RELEASE) return;
    ViewerShell* shell = shell_of(w);
    shell->read_window_input();
    mjuiState& s = shell->ui_.input();
    s.type = mjEVENT_KEY;
    s.key = key;
    s.keytime = glfwGetTime();
    shell->guarded([shell] { shell->on_event(); });
  });
  glfwSetMouseButtonCallback(window, [](GLFWwindow* w, int button, int act, int) {
    ViewerShell* shell = shell_of(w);
    shell->read_window_input();
    const mjuiState& s = shell->ui_.input();
    const int b = button == GLFW_MOUSE_BUTTON_LEFT    ? mjBUTTON_LEFT
                  : button == GLFW_MOUSE_BUTTON_RIGHT ? mjBUTTON_RIGHT
                                                      : mjBUTTON_MIDDLE;
    const double x = s.x, y = s.y;
    if (act == GLFW_PRESS) {
      shell->guarded([=] { shell->press(b, x, y); });
    } else {
      shell->guarded([=] { shell->release(x, y); });
    }
  });
  glfwSetCursorPosCallback(window, [](GLFWwindow* w, double, double) {
    ViewerShell* shell = shell_of(w);
    mjuiState& s = shell->ui_.input();
    if (!s.left && !s.right && !s.middle) return;  // only drags matter
    shell->read_window_input();
    s.type = mjEVENT_MOVE;
    shell->guarded([shell] { shell->on_event(); });
  });
  glfwSetScrollCallback(window, [](GLFWwindow* w, double sx, double sy) {
    ViewerShell* shell = shell_of(w);
    shell->read_window_input();
    mjuiState& s = shell->ui_.input();
    s.type = mjEVENT_SCROLL;
    s.sx = sx * shell->buffer_to_window_;
    s.sy = sy * shell->buffer_to_window_;
    shell->guarded([shell] { shell->on_event(); });
  });
  glfwSetFramebufferSizeCallback(window, [](GLFWwindow* w, int width, int height) {
    ViewerShell* shell = shell_of(w);
    shell->ui_.layout(width, height);
    mjuiState& s = shell->ui_.input();
    s.type = mjEVENT_RESIZE;
    s.dragrect = 0;
    s.dragbutton = 0;
  });
}

// buttons, modifiers and pointer from the window (framebuffer pixels, y up)
void ViewerShell::read_window_input() {
  GLFWwindow* w = window_.get();
  mjuiState& s = ui_.input();
  s.left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
  s.right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
  s.middle = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_MIDDLE) == GLFW_PRESS;
  s.control = glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
              glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
  s.shift = glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
            glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  s.alt = glfwGetKey(w, GLFW_KEY_LEFT_ALT) == GLFW_PRESS ||
          glfwGetKey(w, GLFW_KEY_RIGHT_ALT) == GLFW_PRESS;
  double x = 0.0, y = 0.0;
  glfwGetCursorPos(w, &x, &y);
  ui_.move_pointer(x * buffer_to_window_, s.rect[rect_window].height - y * buffer_to_window_);
}

void ViewerShell::press(int button, double x, double y, bool control) {
  mjuiState& s = ui_.input();
  ui_.move_pointer(x, y);
  s.left = button == mjBUTTON_LEFT;
  s.right = button == mjBUTTON_RIGHT;
  s.middle = button == mjBUTTON_MIDDLE;
  s.control = control ? 1 : s.control;
  s.type = mjEVENT_PRESS;
  // a second press of the same button in the 3-D view within a third of a second is a
  // double-click (a selection), for a driver that selects bodies
  constexpr double kDoubleClick = 0.3;  // [s]
  s.doubleclick = driver_->perturbs() && s.mouserect == rect_view && button == s.button &&
                  clock_ - s.buttontime < kDoubleClick;
  s.button = button;
  s.buttontime = clock_;
  if (s.mouserect != 0) {
    s.dragbutton = button;
    s.dragrect = s.mouserect;
  }
  on_event();
}

void ViewerShell::move_to(double x, double y) {
  ui_.move_pointer(x, y);
  ui_.input().type = mjEVENT_MOVE;
  on_event();
}

void ViewerShell::release(double x, double y) {
  mjuiState& s = ui_.input();
  ui_.move_pointer(x, y);
  s.left = s.right = s.middle = 0;
  s.type = mjEVENT_RELEASE;
  on_event();
  s.dragrect = 0;
  s.dragbutton = 0;
  if (pert_.active != 0) {  // the drag ends: so does the spring
    pert_.active = 0;
    driver_->set_perturbation(pert_);
  }
}

void ViewerShell::on_event() {
  mjuiState& s = ui_.input();
  if (s.type == mjEVENT_KEY) {
    on_key(s.key, s.shift != 0);
    return;
  }
  if (s.type == mjEVENT_RESIZE || s.type == mjEVENT_NONE) return;
  const bool panel = s.dragrect == rect_panel || (s.dragrect == 0 && s.mouserect == rect_panel);
  if (panel) {
    on_panel(ui_.action(mjui_event(&ui_.ui(), &s, &con_)));
    return;
  }
  const mjModel& m = driver_->robot().model();
  if (s.type == mjEVENT_SCROLL) {
    mjv_moveCamera(&m, mjMOUSE_ZOOM, 0.0, -0.05 * s.sy, &camera_);
    driver_->camera_moved(camera_);
    refresh_panel_ = true;
  } else if (s.type == mjEVENT_PRESS && s.mouserect == rect_view && driver_->perturbs()) {
    on_view_press();
  } else if (s.type == mjEVENT_MOVE && s.dragrect == rect_view && pert_.active != 0) {
    // as simulate: right translates the spring's anchor, left turns it (shift: horizontal plane)
    const int action = s.right ? (s.shift ? mjMOUSE_MOVE_H : mjMOUSE_MOVE_V)
                               : (s.shift ? mjMOUSE_ROTATE_H : mjMOUSE_ROTATE_V);
    const double h = std::max(1, ui_.view().height);
    mjv_movePerturb(&m, &driver_->data(), action, s.dx / h, -s.dy / h, &scene_, &pert_);
    driver_->set_perturbation(pert_);
  } else if (s.type == mjEVENT_MOVE && s.dragrect == rect_view) {
    int action = mjMOUSE_NONE;
    if (s.left) {
      action = s.shift ? mjMOUSE_ROTATE_H : mjMOUSE_ROTATE_V;
    } else if (s.right) {
      action = s.shift ? mjMOUSE_MOVE_H : mjMOUSE_MOVE_V;
    } else if (s.middle) {
      action = mjMOUSE_ZOOM;
    }
    const double h = std::max(1, ui_.view().height);
    if (action != mjMOUSE_NONE) {
      mjv_moveCamera(&m, action, s.dx / h, -s.dy / h, &camera_);
      driver_->camera_moved(camera_);
      refresh_panel_ = true;
    }
  }
}

// Ctrl + a button with a body selected starts a drag: right translates, left rotates (simulate's
// bindings); else a double-click selects the body under the pointer (or clears the selection)
void ViewerShell::on_view_press() {
  const mjuiState& s = ui_.input();
  const mjModel& m = driver_->robot().model();
  mjData& d = driver_->data();
  if (s.control != 0 && pert_.select > 0 && (s.left || s.right)) {
    mjv_initPerturb(&m, &d, &scene_, &pert_);
    pert_.active = s.right ? mjPERT_TRANSLATE : mjPERT_ROTATE;
    driver_->set_perturbation(pert_);
    return;
  }
  if (s.doubleclick != 0) {
    const mjrRect view = ui_.view();
    mjtNum point[3] = {0.0, 0.0, 0.0};
    int geom = -1, flex = -1, skin = -1;  // (MuJoCo 4.0.1 writes them all, whatever it says)
    const int body = mjv_select(
        &m, &d, &vis_, static_cast<mjtNum>(view.width) / std::max(1, view.height),
        (s.x - view.left) / std::max(1, view.width), (s.y - view.bottom) / std::max(1, view.height),
        &scene_, point, &geom, &flex, &skin);
    pert_.active = 0;
    pert_.select = body > 0 ? body : 0;
    pert_.flexselect = -1;
    pert_.skinselect = -1;
    if (body > 0) {
      // the grabbed point in the body's frame: the spring pulls there
      mjtNum offset[3];
      mju_sub3(offset, point, d.xpos + 3 * body);
      mju_mulMatTVec(pert_.localpos, d.xmat + 9 * body, offset, 3, 3);
    }
    driver_->set_perturbation(pert_);
  }
}

void ViewerShell::on_key(int key, bool shift) {
  switch (key) {
    case GLFW_KEY_SPACE:
      paused_ = !paused_;
      break;
    case GLFW_KEY_RIGHT:
      if (paused_) driver_->step(1);
      break;
    case GLFW_KEY_BACKSPACE:
      reset();
      break;
    case GLFW_KEY_ESCAPE:
      quit_ = true;
      ended_by_ = "escape";
      break;
    default:
      if (driver_->on_key(key, shift)) changed();
      break;
  }
}

void ViewerShell::on_panel(PanelAction action) {
  switch (action) {
    case PanelAction::none:
      break;
    case PanelAction::pause:
      paused_ = !paused_;
      break;
    case PanelAction::step:
      paused_ = true;
      driver_->step(1);
      break;
    case PanelAction::reset:
      reset();
      break;
    case PanelAction::target:
    case PanelAction::mode:
    case PanelAction::priority:
    case PanelAction::camera:
    case PanelAction::camera_preset:
    case PanelAction::hand:
      driver_->on_panel(action, camera_);
      changed();
      break;
  }
}

void ViewerShell::reset() {
  driver_->reset();
  schedule_.clear_backlog();
  changed();
}

}  // namespace mjarm::detail
