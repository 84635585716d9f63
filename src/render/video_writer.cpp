#include "mjarm/render/video_writer.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <vector>

#include "executable_on_path.hpp"
#include "mjarm/error.hpp"
#include "quoted_path.hpp"

extern char** environ;

namespace mjarm {
namespace {

// The executable to run: @p name itself when it holds a '/', else the first match on PATH.
std::string find_executable(const std::string& name) {
  const std::string hint =
      "; video needs Debian's package `ffmpeg` (apt-get install ffmpeg, or scripts/setup.sh)";
  if (name.find('/') != std::string::npos) {
    if (::access(name.c_str(), X_OK) == 0) return name;
    throw Error("ffmpeg not found: '" + name + "' is not an executable file" + hint);
  }
  std::string found = executable_on_path(name);
  if (found.empty()) throw Error("ffmpeg not found: no '" + name + "' on PATH" + hint);
  return found;
}

// Reads what ffmpeg wrote to its stderr file (the last lines matter: they say why it stopped).
std::string read_all(int fd) {
  std::string text;
  if (fd < 0 || ::lseek(fd, 0, SEEK_SET) < 0) return text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd, buffer, sizeof buffer);
    if (n > 0) {
      text.append(buffer, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;
    }
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  constexpr std::size_t kTail = 2000;
  if (text.size() > kTail) text = "…" + text.substr(text.size() - kTail);
  return text;
}

std::string describe_status(int status) {
  if (WIFEXITED(status)) return "exit status " + std::to_string(WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status));
  return "status " + std::to_string(status);
}

}  // namespace

struct VideoWriter::Impl {
  std::filesystem::path path;
  int width = 0;
  int height = 0;
  double fps = 0.0;
  pid_t pid = -1;
  int pipe_fd = -1;    // write end of ffmpeg's stdin
  int stderr_fd = -1;  // unlinked temporary file holding ffmpeg's stderr
  std::int64_t frames = 0;

  ~Impl() {
    if (pid >= 0) {
      try {
        finish();
      } catch (const std::exception& e) {
        std::cerr << "mjarm: warning: " << e.what() << '\n';
      }
    }
    if (pipe_fd >= 0) ::close(pipe_fd);
    if (stderr_fd >= 0) ::close(stderr_fd);
  }

  // Closes ffmpeg's input and waits for it; returns its wait status.
  int reap() noexcept {
    if (pipe_fd >= 0) ::close(pipe_fd);
    pipe_fd = -1;
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    pid = -1;
    return status;
  }

  void finish() {
    const int status = reap();
    const std::string log = read_all(stderr_fd);
    ::close(stderr_fd);
    stderr_fd = -1;
    if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0))
      throw Error("ffmpeg failed to finalize video " + quoted(path) + " after " +
                  std::to_string(frames) + " frames (" + describe_status(status) +
                  "): " + (log.empty() ? "no message" : log));
  }
};

VideoWriter::VideoWriter(const std::filesystem::path& path, int width, int height, double fps,
                         VideoOptions options) {
  if (width <= 0 || height <= 0)
    throw Error("video frame size must be positive, got " + std::to_string(width) + "×" +
                std::to_string(height) + " for " + quoted(path));
  if (width % 2 != 0 || height % 2 != 0)
    throw Error("video frame size must be even in both directions (yuv420p MP4), got " +
                std::to_string(width) + "×" + std::to_string(height) + " for " + quoted(path) +
                "; try " + std::to_string(width + width % 2) + "×" +
                std::to_string(height + height % 2));
  if (!std::isfinite(fps) || !(fps > 0.0))
    throw Error("video frame rate must be a finite number > 0 frames/s, got " +
                std::to_string(fps) + " for " + quoted(path));
  // prove the path writable now, before any frame, with the system's reason when it is not
  {
    const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw Error("cannot write video " + quoted(path) + ": " + std::strerror(errno));
    ::close(fd);
  }
  const std::string ffmpeg = find_executable(options.ffmpeg);

  auto impl = std::make_unique<Impl>();
  impl->path = path;
  impl->width = width;
  impl->height = height;
  impl->fps = fps;

  // ffmpeg's stderr goes to an unlinked temporary file: read back for error messages, and a
  // chatty ffmpeg can never block on a full pipe
  const char* tmp = std::getenv("TMPDIR");
  std::string log_template =
      std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/mjarm-ffmpeg-XXXXXX";
  impl->stderr_fd = ::mkostemp(log_template.data(), O_CLOEXEC);
  if (impl->stderr_fd < 0)
    throw Error("cannot create a temporary file for ffmpeg's messages: " +
                std::string(std::strerror(errno)));
  ::unlink(log_template.c_str());

  // close-on-exec, so that a second writer's ffmpeg does not inherit (and hold open) this pipe
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0)
    throw Error("cannot create a pipe to ffmpeg: " + std::string(std::strerror(errno)));
  // room for a whole frame, so ffmpeg and the renderer overlap (best effort)
  ::fcntl(fds[1], F_SETPIPE_SZ, width * height * 3);

  std::ostringstream rate;
  rate.precision(17);
  rate << fps;
  const bool x264 = options.codec == "libx264";
  std::vector<std::string> args = {
      ffmpeg,       "-hide_banner", "-nostats",
      "-loglevel",  "error",        "-y",
      "-f",         "rawvideo",     "-pix_fmt",
      "rgb24",      "-video_size",  std::to_string(width) + "x" + std::to_string(height),
      "-framerate", rate.str(),     "-i",
      "pipe:0",     "-an",          "-c:v",
      options.codec};
  if (x264) {
    args.insert(args.end(), {"-preset", "veryfast", "-crf", std::to_string(options.quality)});
  } else {
    const int q = options.quality == 20 ? 4 : options.quality;
    args.insert(args.end(), {"-q:v", std::to_string(q)});
  }
  // "file:" keeps ffmpeg from reading a ':' in the name as a protocol
  args.insert(args.end(), {"-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4",
                           "file:" + path.string()});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  posix_spawn_file_actions_adddup2(&actions, impl->stderr_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, impl->stderr_fd, STDERR_FILENO);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  // own process group: a terminal's Ctrl-C stops the program, and ffmpeg then finalizes on EOF
  posix_spawnattr_setpgroup(&attributes, 0);
  sigset_t defaults, empty;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  sigaddset(&defaults, SIGINT);
  sigemptyset(&empty);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setsigmask(&attributes, &empty);
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK);
  pid_t pid = -1;
  const int spawned =
      ::posix_spawn(&pid, ffmpeg.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  ::close(fds[0]);
  if (spawned != 0) {
    ::close(fds[1]);
    throw Error("cannot start ffmpeg ('" + ffmpeg + "'): " + std::strerror(spawned));
  }
  impl->pid = pid;
  impl->pipe_fd = fds[1];
  impl_ = std::move(impl);
}

VideoWriter::~VideoWriter() = default;
VideoWriter::VideoWriter(VideoWriter&&) noexcept = default;
VideoWriter& VideoWriter::operator=(VideoWriter&&) noexcept = default;

void VideoWriter::write(const Image& frame) {
  if (!impl_ || impl_->pid < 0) throw Error("VideoWriter used after close()");
  Impl& s = *impl_;
  if (frame.width != s.width || frame.height != s.height || frame.rgb.size() != frame.pixels() * 3)
    throw Error("video frame of " + std::to_string(frame.width) + "×" +
                std::to_string(frame.height) + " pixels does not match the video's " +
                std::to_string(s.width) + "×" + std::to_string(s.height) + " (" + quoted(s.path) +
                ")");

  // a dead reader raises SIGPIPE, whose default action kills the process: block it on this
  // thread while writing, and take back any SIGPIPE the write left pending
  sigset_t pipe_signal, previous;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &previous);
  const std::uint8_t* data = frame.rgb.data();
  std::size_t left = frame.rgb.size();
  int error = 0;
  while (left > 0) {
    const ssize_t n = ::write(s.pipe_fd, data, left);
    if (n < 0) {
      if (errno == EINTR) continue;
      error = errno;
      break;
    }
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (error == EPIPE && !sigismember(&previous, SIGPIPE)) {
    const timespec no_wait{0, 0};
    while (sigtimedwait(&pipe_signal, nullptr, &no_wait) < 0 && errno == EINTR) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  if (error == 0) {
    ++s.frames;
    return;
  }

  // ffmpeg went away (or the pipe broke): collect its reason and close
  const int status = s.reap();
  const std::string log = read_all(s.stderr_fd);
  ::close(s.stderr_fd);
  s.stderr_fd = -1;
  throw Error("ffmpeg stopped while receiving frame " + std::to_string(s.frames) + " of " +
              quoted(s.path) + " (" + std::strerror(error) + ", ffmpeg " + describe_status(status) +
              "): " + (log.empty() ? "no message" : log));
}

void VideoWriter::close() {
  if (!impl_ || impl_->pid < 0) return;
  impl_->finish();
}

bool VideoWriter::is_open() const noexcept { return impl_ && impl_->pid >= 0; }
std::int64_t VideoWriter::frames() const noexcept { return impl_ ? impl_->frames : 0; }
const std::filesystem::path& VideoWriter::path() const noexcept {
  static const std::filesystem::path none;
  return impl_ ? impl_->path : none;
}
int VideoWriter::width() const noexcept { return impl_ ? impl_->width : 0; }
int VideoWriter::height() const noexcept { return impl_ ? impl_->height : 0; }
double VideoWriter::fps() const noexcept { return impl_ ? impl_->fps : 0.0; }

}  // namespace mjarm
