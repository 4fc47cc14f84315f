// For tests that run our programs as processes: start one with its output appended to files,
// signal it, wait for its exit with a deadline (a hung program fails the test instead of
// hanging ctest; one still running when the Process goes away is killed).
#pragma once

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace fleetmap::testing {

class Process {
 public:
  // Starts `args[0] args...` (a path) with stdout and stderr appended to the given files.
  Process(const std::vector<std::string>& args, const std::string& stdout_path,
          const std::string& stderr_path) {
    // Everything the child needs is made before fork: between fork and exec only
    // async-signal-safe calls are allowed (the test may run threads).
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const int out = ::open(stdout_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    const int err = ::open(stderr_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(out, 1);
      ::dup2(err, 2);
      ::execv(argv[0], argv.data());
      ::_exit(127);
    }
    ::close(out);
    ::close(err);
  }
  Process(const Process&) = delete;
  Process& operator=(const Process&) = delete;
  ~Process() {
    if (running()) {
      ::kill(pid_, SIGKILL);
      Wait(10.0);
    }
  }
  bool started() const { return pid_ > 0; }
  bool running() const { return pid_ > 0 && !exited_; }
  void Signal(int sig) {
    if (running()) ::kill(pid_, sig);
  }
  // The exit status (or 128 + signal), -1 if still running after timeout_s.
  int Wait(double timeout_s) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (!exited_) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_) {
        exited_ = true;
        code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        break;
      }
      if (std::chrono::steady_clock::now() > end) return -1;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return code_;
  }

 private:
  pid_t pid_ = -1;
  bool exited_ = false;
  int code_ = -1;
};

// Runs `args` to its end: the exit status, or -1 if it ran longer than timeout_s (then killed).
inline int RunToExit(const std::vector<std::string>& args, const std::string& stdout_path,
                     const std::string& stderr_path, double timeout_s) {
  Process p(args, stdout_path, stderr_path);
  return p.Wait(timeout_s);
}

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace fleetmap::testing
