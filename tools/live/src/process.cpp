#include "process.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include "vt/core/clock.hpp"
#include "vt/core/error.hpp"

namespace vt::live {
namespace fs = std::filesystem;
namespace {

pid_t spawn(const std::vector<std::string>& args, const std::vector<std::string>& env, const fs::path& out, const fs::path& err) {
  const int outFd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int errFd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (outFd < 0 || errFd < 0) fail("live: cannot create ", out.string(), ": ", std::strerror(errno));
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) fail("live: fork: ", std::strerror(errno));
  if (pid == 0) {
    ::setpgid(0, 0);  // its own group: a timeout kills xvfb-run, Xvfb and the program together
    ::dup2(outFd, 1);
    ::dup2(errFd, 2);
    for (const std::string& e : env) ::putenv(const_cast<char*>(e.c_str()));
    ::execvp(argv[0], argv.data());
    std::fprintf(stderr, "cannot run %s: %s\n", argv[0], std::strerror(errno));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  ::close(outFd);
  ::close(errFd);
  return pid;
}

// Waits up to timeout_s; the exit status, or -1 when still running.
int waitFor(pid_t pid, double timeout_s) {
  const std::int64_t end = SteadyClock::instance().now_ns() + std::int64_t(timeout_s * 1e9);
  for (;;) {
    int status = 0;
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) return status;
    if (SteadyClock::instance().now_ns() > end) return -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void killGroup(pid_t pid) {
  ::kill(-pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
}

std::string describe(int status) {
  if (WIFEXITED(status)) return str("exit code ", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return str("signal ", WTERMSIG(status));
  return "an unknown status";
}

}  // namespace

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

std::vector<std::string> withXvfb(std::vector<std::string> args) {
  args.insert(args.begin(), {"xvfb-run", "-a", "-s", "-screen 0 1280x800x24"});
  return args;
}

void runToEnd(const std::vector<std::string>& args, const std::vector<std::string>& env, const fs::path& out,
              const fs::path& err, double timeout_s) {
  const pid_t pid = spawn(args, env, out, err);
  const int status = waitFor(pid, timeout_s);
  if (status < 0) {
    killGroup(pid);
    fail("live: ", args[0], " ", args.size() > 1 ? args[1] : "", " ran past ", timeout_s, " s (killed); see ", err.string());
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    fail("live: ", args[0], " ", args.size() > 1 ? args[1] : "", " ended with ", describe(status), "; see ", err.string());
}

Background::Background(const std::vector<std::string>& args, fs::path out, fs::path err)
    : m_pid(spawn(args, {}, out, err)), m_out(std::move(out)), m_err(std::move(err)) {}

Background::~Background() {
  if (m_pid > 0) killGroup(m_pid);
}

std::string Background::waitForLine(const std::string& prefix, const std::string& marker, double timeout_s) {
  const std::int64_t end = SteadyClock::instance().now_ns() + std::int64_t(timeout_s * 1e9);
  while (SteadyClock::instance().now_ns() < end) {
    std::ifstream in(m_out);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind(prefix, 0) != 0) continue;
      const std::size_t at = line.find(marker);
      if (at == std::string::npos) continue;
      const std::size_t from = at + marker.size();
      return line.substr(from, line.find(' ', from) - from);
    }
    int status = 0;
    if (::waitpid(m_pid, &status, WNOHANG) == m_pid) {
      m_pid = -1;
      fail("live: the server ended with ", describe(status), " before it served; see ", m_err.string());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  fail("live: the server did not start within ", timeout_s, " s; see ", m_err.string());
}

void Background::stop(double timeout_s) {
  if (m_pid <= 0) return;
  ::kill(m_pid, SIGINT);
  const int status = waitFor(m_pid, timeout_s);
  const pid_t pid = m_pid;
  m_pid = -1;
  if (status < 0) {
    killGroup(pid);
    fail("live: the server did not stop within ", timeout_s, " s of Ctrl-C; see ", m_err.string());
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    fail("live: the server ended with ", describe(status), "; see ", m_err.string());
}

}  // namespace vt::live
