#include "modes/video_encoder.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"
#include "vt/core/stop.hpp"

namespace vt::app {
namespace fs = std::filesystem;
namespace {

constexpr int kPollSlice_ms = 100;  // how often a wait looks at the stop request

std::int64_t now_ms() { return SteadyClock::instance().now_ns() / 1'000'000; }

std::string exitText(int status) {
  if (WIFEXITED(status)) return str("exit status ", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return str("killed by signal ", WTERMSIG(status));
  return "stopped";
}

}  // namespace

fs::path findFfmpeg() {
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "/usr/bin:/bin";
  for (std::size_t begin = 0; begin <= dirs.size();) {
    const std::size_t colon = std::min(dirs.find(':', begin), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(begin, colon - begin)) / "ffmpeg";
    if (colon > begin && ::access(candidate.c_str(), X_OK) == 0) return candidate;
    begin = colon + 1;
  }
  return {};
}

VideoEncoder::VideoEncoder(const fs::path& path, int width, int height, double fps, const char* command)
    : m_path(path), m_command(str(command, ": --video ", path.string())) {
  const fs::path ffmpeg = findFfmpeg();
  if (ffmpeg.empty()) fail(command, ": --video needs the ffmpeg program (Debian package ffmpeg)");
  m_partial = path.parent_path() / (path.stem().string() + ".partial" + path.extension().string());
  std::error_code ec;
  if (path.has_parent_path()) fs::create_directories(path.parent_path(), ec);
  char size[32], rate[32];
  std::snprintf(size, sizeof size, "%dx%d", width, height);
  std::snprintf(rate, sizeof rate, "%.6g", fps);
  const std::vector<std::string> argv = {ffmpeg.string(), "-nostdin", "-loglevel", "error", "-y", "-f", "rawvideo",
                                         "-pixel_format", "rgba", "-video_size", size, "-framerate", rate,
                                         "-i", "pipe:0", "-pix_fmt", "yuv420p", m_partial.string()};
  // Everything the child needs is built before fork: between fork and exec only
  // async-signal-safe calls (the renderer's threads may hold the allocator's lock).
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) fail(m_command, ": pipe: ", std::strerror(errno));
  // A dead ffmpeg makes writes fail with EPIPE (reported below), not kill the run.
  std::signal(SIGPIPE, SIG_IGN);
  const pid_t parent = ::getpid();
  m_pid = ::fork();
  if (m_pid < 0) {
    ::close(fds[0]), ::close(fds[1]);
    fail(m_command, ": fork: ", std::strerror(errno));
  }
  if (m_pid == 0) {
    // Its own process group (the terminal's Ctrl-C reaches this process, which stops it), and
    // killed when this process dies however it dies (no orphan encoder).
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl
    ::dup2(fds[0], STDIN_FILENO);
    ::execv(args[0], args.data());
    ::_exit(127);
  }
  ::close(fds[0]);
  m_fd = fds[1];
  ::fcntl(m_fd, F_SETFL, ::fcntl(m_fd, F_GETFL) | O_NONBLOCK);  // writes wait in poll(), bounded
}

VideoEncoder::~VideoEncoder() {
  kill();
  std::error_code ec;
  fs::remove(m_partial, ec);
}

void VideoEncoder::kill() noexcept {
  if (m_fd >= 0) ::close(m_fd);
  m_fd = -1;
  if (m_pid <= 0) return;
  ::kill(-m_pid, SIGKILL);
  ::kill(m_pid, SIGKILL);
  int status = 0;
  while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {}
  m_pid = -1;
}

void VideoEncoder::failAndKill(const std::string& why) {
  kill();
  fail(m_command, ": ", why);
}

void VideoEncoder::write(const Image8& frame) {
  if (m_fd < 0) fail(m_command, ": write after finish");
  const auto* bytes = frame.pixels.data();
  std::size_t left = frame.pixels.size();
  std::int64_t progress_ms = now_ms();
  while (left > 0) {
    if (stopRequested()) return;
    const ssize_t n = ::write(m_fd, bytes, left);
    if (n > 0) {
      bytes += n;
      left -= std::size_t(n);
      progress_ms = now_ms();
      continue;
    }
    if (n < 0 && errno == EPIPE) {
      int status = 0;
      while (::waitpid(m_pid, &status, 0) < 0 && errno == EINTR) {}
      m_pid = -1;
      failAndKill(str("ffmpeg stopped reading frames (", exitText(status), "; its message is above)"));
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) failAndKill(str("writing to ffmpeg: ", std::strerror(errno)));
    if (now_ms() - progress_ms > kStall_ms) {
      failAndKill(str("ffmpeg read nothing for ", kStall_ms / 1000, " s (stalled); it was stopped"));
    }
    pollfd wait{m_fd, POLLOUT, 0};
    ::poll(&wait, 1, kPollSlice_ms);
  }
}

// Waits for ffmpeg to exit while its partial file grows; `stalled` when it stopped growing for
// kStall_ms, or ffmpeg outlived kStopGrace_ms after the stop request. Returns the wait status.
int VideoEncoder::waitExit(bool& stalled) {
  std::int64_t progress_ms = now_ms(), stop_ms = -1;
  std::uintmax_t size = 0;
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(m_pid, &status, WNOHANG);
    if (done == m_pid) {
      m_pid = -1;
      return status;
    }
    if (done < 0 && errno != EINTR) return -1;
    std::error_code ec;
    if (const std::uintmax_t now = fs::file_size(m_partial, ec); !ec && now != size) size = now, progress_ms = now_ms();
    if (stopRequested() && stop_ms < 0) stop_ms = now_ms();
    if (now_ms() - progress_ms > kStall_ms || (stop_ms >= 0 && now_ms() - stop_ms > kStopGrace_ms)) {
      stalled = true;
      return -1;
    }
    ::usleep(kPollSlice_ms * 1000 / 4);
  }
}

void VideoEncoder::finish() {
  ::close(m_fd);
  m_fd = -1;
  bool stalled = false;
  const int status = waitExit(stalled);
  if (stalled && stopRequested()) failAndKill("ffmpeg did not finish the video after the stop request; it was stopped");
  if (stalled) failAndKill(str("ffmpeg wrote nothing for ", kStall_ms / 1000, " s after the last frame (stalled); it was stopped"));
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    fail(m_command, ": ffmpeg failed (", exitText(status), "; its message is above)");
  std::error_code ec;
  fs::rename(m_partial, m_path, ec);
  if (ec) fail(m_command, ": cannot move ", m_partial.string(), " to ", m_path.string(), ": ", ec.message());
}

}  // namespace vt::app
