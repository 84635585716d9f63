// The viewer's loop (wall clock or virtual clock) and the script runner.
#include "mjarm/teleop/viewer.hpp"

#include <GLFW/glfw3.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <thread>
#include <utility>

#include "mjarm/error.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/render/png.hpp"
#include "viewer_shell.hpp"

namespace mjarm {

const char* const kNoDisplayMessage =
    "no display: set DISPLAY or run under xvfb-run; for headless images use `mjarm render`";

void require_display() {
  const char* display = std::getenv("DISPLAY");
  if (display == nullptr || display[0] == '\0') throw Error(kNoDisplayMessage);
}

bool has_several_hands(const Robot& robot) {
  try {
    return find_teleop_hands(robot).size() > 1;
  } catch (const Error&) {
    return false;  // no hand frame at all: the single-arm viewer says what it needs
  }
}

ViewerReport run_viewer(const Robot& robot, const ViewerOptions& options) {
  require_display();
  // Ctrl-C ends the session with its report (and its recording) from here on: also while the
  // session and the window are being built, which takes seconds on a slow machine
  const InterruptGuard interrupt_guard;
  detail::ViewerShell shell(robot, options);
  try {
    return shell.run();
  } catch (...) {
    shell.save();  // what was recorded up to the error is written
    throw;
  }
}

namespace detail {

namespace {

int mouse_button(const std::string& name) {
  return name == "left" ? mjBUTTON_LEFT : name == "right" ? mjBUTTON_RIGHT : mjBUTTON_MIDDLE;
}

}  // namespace

ViewerReport ViewerShell::run() {
  // a script runs on a virtual clock (deterministic, as fast as frames are drawn) unless the
  // driver shows a loop that runs on the wall clock
  const bool scripted = options_.script.has_value() && driver_->virtual_clock();
  const double wall_start = glfwGetTime();
  clock_ = scripted ? 0.0 : wall_start;
  for (const auto& [name, value] : options_.set) {
    ScriptCommand command;
    command.action = ScriptAction::set;
    command.name = name;
    command.value = value;
    execute(command);
  }
  schedule_ = ViewerSchedule(options_.rates, driver_->control_period(), clock_);
  while (!quit_) {
    if (!scripted) clock_ = glfwGetTime();
    driver_->update();
    const ScheduleStep step = schedule_.update(clock_, paused_);
    if (step.poll_input) {
      glfwPollEvents();
      if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
      if (glfwWindowShouldClose(window_.get())) {
        quit_ = true;
        ended_by_ = "window closed";
      } else if (driver_->finished()) {
        quit_ = true;
        ended_by_ = "closed by the program";
      } else if (interrupt_requested()) {
        quit_ = true;
        ended_by_ = "interrupted";
        report_.signal = interrupt_signal();
      }
      if (options_.script && !quit_) run_script();
      driver_->read_panel();  // the panel is read at the input rate
    }
    if (quit_) break;
    const int ticks = paused_ ? 0 : driver_->step(step.ticks);  // a pause takes effect at once
    // the meters use the real clock, also in scripted runs: they report what the machine does
    const double wall = glfwGetTime();
    speed_.add(wall, ticks * driver_->control_period());
    if (step.render) {
      render(nullptr);
      fps_.add(wall);
    }
    // a script's wait counts frames: resume it as soon as they are drawn, not at the next input
    // poll (rendering at 1000 Hz with input at 20 Hz, that came 50 frames later)
    if (options_.script && step.render && frames_ >= wait_until_) run_script();
    if (scripted) {
      clock_ = schedule_.next_due();  // jump straight to the next event
    } else {
      const double wait = schedule_.next_due() - glfwGetTime();
      if (wait > 0.0)
        std::this_thread::sleep_for(std::chrono::duration<double>(std::min(wait, 0.05)));
    }
  }
  report_.ended_by = ended_by_;
  report_.frames = frames_;
  report_.polls = schedule_.polls();
  report_.ticks = schedule_.ticks();
  report_.wall_seconds = glfwGetTime() - wall_start;
  report_.dropped = schedule_.dropped();
  report_.gl = gl_;
  driver_->finish(report_);
  return report_;
}

// runs script commands until one waits for frames, or the script ends
void ViewerShell::run_script() {
  const auto& commands = options_.script->commands;
  while (!quit_ && frames_ >= wait_until_) {
    if (next_command_ >= commands.size()) {
      quit_ = true;
      ended_by_ = "end of script";
      return;
    }
    const ScriptCommand& command = commands[next_command_++];
    try {
      execute(command);
    } catch (const Error& e) {
      throw Error("viewer script, line " + std::to_string(command.line) + " (" +
                  to_string(command.action) + "): " + e.what());
    }
  }
}

void ViewerShell::execute(const ScriptCommand& c) {
  const mjrRect view = ui_.view();
  const double cx = view.left + 0.5 * view.width;
  const double cy = view.bottom + 0.5 * view.height;
  switch (c.action) {
    case ScriptAction::wait:
      wait_until_ = frames_ + c.frames;
      break;
    case ScriptAction::set:
      try {
        driver_->set_value(c.name, c.value, camera_);
      } catch (...) {
        changed();  // a mode refused still changed the note and the panel
        throw;
      }
      changed();
      break;
    case ScriptAction::slider: {
      const auto point = ui_.slider_point(c.name, c.x);
      if (!point) throw Error("no slider '" + c.name + "' on the panel");
      press(mjBUTTON_LEFT, (*point)[0], (*point)[1]);
      release((*point)[0], (*point)[1]);
      break;
    }
    case ScriptAction::key: {
      mjuiState& s = ui_.input();
      s.type = mjEVENT_KEY;
      s.key = viewer_key_code(c.name);
      s.keytime = clock_;
      const int shift = s.shift;
      s.shift = c.value == "shift" ? 1 : 0;  // "key shift+w"
      on_event();
      s.shift = shift;
      break;
    }
    case ScriptAction::drag: {
      press(mouse_button(c.name), cx, cy);
      constexpr int kSteps = 10;  // a drag is a series of moves, as a hand makes it
      for (int k = 1; k <= kSteps; ++k) move_to(cx + c.x * k / kSteps, cy - c.y * k / kSteps);
      release(cx + c.x, cy - c.y);
      break;
    }
    case ScriptAction::select:
      // two presses at one clock: a double-click
      for (int k = 0; k < 2; ++k) {
        press(mjBUTTON_LEFT, cx + c.x, cy - c.y);
        release(cx + c.x, cy - c.y);
      }
      break;
    case ScriptAction::press:
      press(mouse_button(c.name), cx + c.x, cy - c.y, c.value == "ctrl");
      break;
    case ScriptAction::move:
      move_to(cx + c.x, cy - c.y);
      break;
    case ScriptAction::release: {
      mjuiState& s = ui_.input();
      release(s.x, s.y);
      s.control = 0;
      break;
    }
    case ScriptAction::scroll: {
      ui_.move_pointer(cx, cy);
      mjuiState& s = ui_.input();
      s.type = mjEVENT_SCROLL;
      s.sx = 0.0;
      s.sy = c.x;
      on_event();
      break;
    }
    case ScriptAction::screenshot:
      screenshot(c.name);
      break;
    case ScriptAction::quit:
      quit_ = true;
      ended_by_ = "quit";
      break;
  }
}

void ViewerShell::screenshot(const std::string& path) {
  driver_->read_panel();
  Image image;
  render(&image);
  write_png(image, path);
  ViewerScreenshot shot;
  shot.path = path;
  shot.frame = frames_;
  driver_->describe(shot);
  shot.width = image.width;
  shot.height = image.height;
  report_.screenshots.push_back(shot);
}

}  // namespace detail
}  // namespace mjarm
