#include "mjarm/render/video_writer.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>
#include <vector>

#include "child_process.hpp"
#include "executable_on_path.hpp"
#include "mjarm/error.hpp"
#include "mjarm/file_writer.hpp"
#include "mjarm/interrupt.hpp"
#include "mjarm/number_text.hpp"
#include "quoted_path.hpp"

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

// The one way a path reaches ffmpeg's command line. ffmpeg gets an argv array (no shell, so
// nothing to quote for one); the "file:" protocol prefix keeps it from reading a ':' in the name
// as a protocol and a leading '-' as an option. Every byte but NUL passes unchanged.
std::string ffmpeg_output(const std::filesystem::path& path) { return "file:" + path.string(); }

using Clock = std::chrono::steady_clock;

// After Ctrl-C or SIGTERM, how long ffmpeg still gets to take a frame or to finalize the file.
constexpr double kInterruptGrace = 3.0;  // [s]

Clock::time_point after(double seconds) {
  return Clock::now() + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double>(std::min(seconds, 1e7)));
}

// @p seconds as a person writes them: "3", "0.5", "60"
std::string seconds_text(double seconds) {
  std::ostringstream text;
  text.precision(3);
  text << seconds;
  return text.str();
}

// The deadline cut to the grace period once an interrupt is pending (the first time it is seen).
void shorten_on_interrupt(Clock::time_point& deadline, bool& interrupted) {
  if (interrupted || !interrupt_requested()) return;
  interrupted = true;
  deadline = std::min(deadline, after(kInterruptGrace));
}

// Why @p path is not a complete MP4 (empty when it is): it must exist, be a non-empty regular
// file, and its top-level boxes (32-bit size, type; size 1: a 64-bit size follows; size 0: to
// the end of the file) must tile the file and include the `moov` box, which ffmpeg writes last
// (or, with +faststart, moves to the front once the rest is written).
std::string mp4_defect(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return std::string("it cannot be opened: ") + std::strerror(errno);
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    ::close(fd);
    return "it is not a regular file";
  }
  const auto size = static_cast<std::uint64_t>(info.st_size);
  std::string defect = size == 0 ? "it is empty" : "";
  bool moov = false;
  std::uint64_t at = 0;
  while (defect.empty() && at < size) {
    unsigned char header[16];
    const ssize_t n = ::pread(fd, header, sizeof header, static_cast<off_t>(at));
    if (n < 8) {
      defect = "it ends inside a box header at byte " + std::to_string(at);
      break;
    }
    std::uint64_t box = 0;
    for (int k = 0; k < 4; ++k) box = box << 8 | header[k];
    std::uint64_t header_size = 8;
    if (box == 1) {
      if (n < 16) {
        defect = "it ends inside a box header at byte " + std::to_string(at);
        break;
      }
      box = 0;
      for (int k = 8; k < 16; ++k) box = box << 8 | header[k];
      header_size = 16;
    } else if (box == 0) {
      box = size - at;
    }
    const std::string type(reinterpret_cast<const char*>(header) + 4, 4);
    if (box < header_size || box > size - at) {
      defect = "its '" + type + "' box at byte " + std::to_string(at) + " claims " +
               std::to_string(box) + " bytes, but the file has " + std::to_string(size - at) +
               " from there (truncated)";
      break;
    }
    moov = moov || type == "moov";
    at += box;
  }
  ::close(fd);
  if (defect.empty() && !moov) defect = "it has no 'moov' box, the index a player needs";
  return defect;
}

}  // namespace

struct VideoWriter::Impl {
  std::filesystem::path path;
  // the hidden temporary file ffmpeg writes, renamed over `path` once checked (file_writer.hpp)
  std::optional<FileWriter> file;
  bool complete = false;
  int width = 0;
  int height = 0;
  double fps = 0.0;
  double timeout_s = 0.0;
  pid_t pid = -1;      // ffmpeg, leading its own process group
  int pipe_fd = -1;    // write end of ffmpeg's stdin, non-blocking
  int stderr_fd = -1;  // unlinked temporary file holding ffmpeg's stderr
  std::int64_t frames = 0;

  ~Impl() {
    // never closed: the video may lack its end (an exception, an early return), so it is not
    // written; an old file at the path keeps its content
    if (pid >= 0) stop(0.0);
    if (pipe_fd >= 0) ::close(pipe_fd);
    if (stderr_fd >= 0) ::close(stderr_fd);
  }

  // ffmpeg's messages so far (the last lines say why it stopped); closes the log
  std::string take_log() {
    const std::string log = read_all(stderr_fd);
    if (stderr_fd >= 0) ::close(stderr_fd);
    stderr_fd = -1;
    return log.empty() ? "no message" : log;
  }

  // Ends ffmpeg's input and gives it @p grace_s to exit; then kills it (and anything it
  // started) and reaps it, and discards what it wrote. Returns its wait status. For the error
  // paths.
  int stop(double grace_s) noexcept {
    if (pipe_fd >= 0) ::close(pipe_fd);
    pipe_fd = -1;
    int status = 0;
    if (grace_s <= 0.0 || !wait_child_until(pid, after(grace_s), status))
      status = kill_child(pid, true);
    pid = -1;
    file.reset();  // removes the temporary file: no cut video is left
    return status;
  }

  // The file ffmpeg writes (the temporary one beside the video).
  const std::filesystem::path& output() const { return file->written_path(); }

  // " (the file already at 'PATH' is kept)" or " (no file was made)": what an unwritten video
  // leaves at its path
  std::string what_is_left() const {
    std::error_code ec;
    return std::filesystem::exists(path, ec) ? " (the file already at " + quoted(path) + " is kept)"
                                             : std::string(" (no file was made)");
  }

  // Closes ffmpeg's input, waits for it to finalize the file (up to the timeout, less after an
  // interrupt), then checks the file itself: ffmpeg's exit status alone misses a full disk. A
  // video closed while an interrupt is pending is cut short: ffmpeg is stopped, nothing written.
  void finish() {
    if (interrupt_requested()) {
      stop(0.0);
      throw Error("video " + quoted(path) + " was not written: interrupted after " +
                  std::to_string(frames) + " frames" + what_is_left());
    }
    if (pipe_fd >= 0) ::close(pipe_fd);
    pipe_fd = -1;
    Clock::time_point deadline = after(timeout_s);
    bool interrupted = false;
    int status = 0;
    for (;;) {
      shorten_on_interrupt(deadline, interrupted);
      const Clock::time_point slice = std::min(deadline, after(0.1));
      if (wait_child_until(pid, slice, status)) break;
      if (Clock::now() < deadline) continue;
      stop(0.0);
      throw Error("ffmpeg did not finalize video " + quoted(path) + " within " +
                  seconds_text(interrupted ? kInterruptGrace : timeout_s) + " s" +
                  (interrupted ? " of the interrupt" : "") + " and was stopped after " +
                  std::to_string(frames) + " frames; no video was written: " + take_log());
    }
    pid = -1;
    const std::string log = take_log();
    if (!(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
      file.reset();
      throw Error("ffmpeg failed to finalize video " + quoted(path) + " after " +
                  std::to_string(frames) + " frames (" + describe_status(status) +
                  "); no video was written: " + log);
    }
    const std::string defect = mp4_defect(output());
    if (!defect.empty()) {
      file.reset();
      throw Error("ffmpeg reported success, but video " + quoted(path) +
                  " is not a complete MP4 (" + defect + ") after " + std::to_string(frames) +
                  " frames, so no video was written; is the disk full? ffmpeg said: " + log);
    }
    // synced and renamed over the video (an old file stays until then); a failure removes it
    file->commit();
    file.reset();
    complete = true;
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
                number_text(fps) + " for " + quoted(path));
  check_fields(options, "video " + quoted(path));
  // ffmpeg first: without it nothing is created
  const std::string ffmpeg = find_executable(options.ffmpeg);

  auto impl = std::make_unique<Impl>();
  impl->path = path;
  // the temporary file ffmpeg writes, beside the video: proves the folder writable now, before
  // any frame, with the system's reason when it is not ("cannot write video 'x.mp4': …")
  impl->file.emplace(path, FileWriter::Mode::replace, "video", 1);
  impl->width = width;
  impl->height = height;
  impl->fps = fps;
  impl->timeout_s = options.timeout_s;

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
  args.insert(args.end(), {"-pix_fmt", "yuv420p", "-movflags", "+faststart", "-f", "mp4",
                           ffmpeg_output(impl->output())});
  // an argv array, never a shell; ffmpeg leads its own process group (a terminal's Ctrl-C
  // reaches mjarm only, which then ends ffmpeg's input) and dies with mjarm (child_process.hpp)
  int error = 0;
  const pid_t pid = start_child(args, {fds[0], impl->stderr_fd, impl->stderr_fd}, true, error);
  ::close(fds[0]);
  if (pid < 0) {
    ::close(fds[1]);
    throw Error("cannot start ffmpeg ('" + ffmpeg + "'): " + std::strerror(error));
  }
  // writes wait with a deadline (poll), never in a blocking write ffmpeg may never drain
  ::fcntl(fds[1], F_SETFL, ::fcntl(fds[1], F_GETFL) | O_NONBLOCK);
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
  Clock::time_point deadline = after(s.timeout_s);
  bool interrupted = false;
  while (left > 0) {
    const ssize_t n = ::write(s.pipe_fd, data, left);
    if (n > 0) {
      data += n;
      left -= static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) {
      error = errno;
      break;
    }
    // the pipe is full: wait for ffmpeg to read, in slices, until the deadline
    shorten_on_interrupt(deadline, interrupted);
    const auto now = Clock::now();
    if (now >= deadline) {
      error = ETIMEDOUT;
      break;
    }
    const auto wait = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - now);
    pollfd ready{s.pipe_fd, POLLOUT, 0};
    ::poll(&ready, 1, static_cast<int>(std::clamp<std::int64_t>(wait.count(), 1, 100)));
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

  if (error == ETIMEDOUT) {
    // ffmpeg stopped reading: it will not finalize the file either
    s.stop(0.0);
    throw Error("ffmpeg did not take frame " + std::to_string(s.frames) + " of " + quoted(s.path) +
                " within " + seconds_text(interrupted ? kInterruptGrace : s.timeout_s) + " s" +
                (interrupted ? " of the interrupt" : "") +
                " and was stopped; no video was written: " + s.take_log());
  }
  // ffmpeg went away (or the pipe broke): collect its reason
  const int status = s.stop(kInterruptGrace);
  throw Error("ffmpeg stopped while receiving frame " + std::to_string(s.frames) + " of " +
              quoted(s.path) + " (" + std::strerror(error) + ", ffmpeg " + describe_status(status) +
              "): " + s.take_log());
}

void VideoWriter::close() {
  if (!impl_ || impl_->pid < 0) return;
  impl_->finish();
}

void VideoWriter::abandon() noexcept {
  if (!impl_ || impl_->pid < 0) return;
  impl_->stop(0.0);
}

bool VideoWriter::is_open() const noexcept { return impl_ && impl_->pid >= 0; }
bool VideoWriter::complete() const noexcept { return impl_ && impl_->complete; }
std::int64_t VideoWriter::frames() const noexcept { return impl_ ? impl_->frames : 0; }
const std::filesystem::path& VideoWriter::path() const noexcept {
  static const std::filesystem::path none;
  return impl_ ? impl_->path : none;
}
int VideoWriter::width() const noexcept { return impl_ ? impl_->width : 0; }
int VideoWriter::height() const noexcept { return impl_ ? impl_->height : 0; }
double VideoWriter::fps() const noexcept { return impl_ ? impl_->fps : 0.0; }

}  // namespace mjarm
