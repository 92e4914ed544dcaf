#include "child_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <thread>

#include "vt/core/error.hpp"

extern char** environ;

namespace vt::test {

ChildResult runChild(const std::vector<std::string>& argv, const std::map<std::string, std::string>& env,
                     const std::filesystem::path& logFile, double timeout_s) {
  int stdinPipe[2];
  if (pipe(stdinPipe) != 0) fail("pipe() failed");
  const int logFd = ::open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (logFd < 0) fail("cannot write ", logFile.string());
  const pid_t pid = fork();
  if (pid < 0) fail("fork() failed");
  if (pid == 0) {
    dup2(stdinPipe[0], 0);
    dup2(logFd, 1);
    dup2(logFd, 2);
    close(stdinPipe[0]);
    close(stdinPipe[1]);
    close(logFd);
    for (const auto& [key, value] : env) setenv(key.c_str(), value.c_str(), 1);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  close(stdinPipe[0]);
  close(logFd);
  ChildResult result;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  int status = 0;
  for (;;) {
    const pid_t done = waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (std::chrono::steady_clock::now() > deadline) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      result.timedOut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  close(stdinPipe[1]);  // only now: closing stdin earlier would make hello_xr quit by itself
  if (!result.timedOut && WIFEXITED(status)) result.exitCode = WEXITSTATUS(status);
  std::ifstream in(logFile);
  std::stringstream text;
  text << in.rdbuf();
  result.output = text.str();
  return result;
}

}  // namespace vt::test
