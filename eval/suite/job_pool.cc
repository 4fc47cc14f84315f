#include "eval/suite/job_pool.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <map>

namespace fleetmap::eval::suite {
namespace {

using Clock = std::chrono::steady_clock;

// Starts a job; its pid, or -1 with `error` set.
pid_t Start(const Job& job, std::string& error) {
  const int out = ::open(job.stdout_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  const int err = ::open(job.stderr_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (out < 0 || err < 0 || job.argv.empty()) {
    error = job.argv.empty() ? "no program"
                             : "cannot open the output files: " + std::string(std::strerror(errno));
    if (out >= 0) ::close(out);
    if (err >= 0) ::close(err);
    return -1;
  }
  std::vector<char*> argv;
  for (const std::string& a : job.argv) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(out, STDOUT_FILENO);
    ::dup2(err, STDERR_FILENO);
    ::execv(argv[0], argv.data());
    const char* why = std::strerror(errno);
    (void)!::write(STDERR_FILENO, "cannot run the program: ", 24);
    (void)!::write(STDERR_FILENO, why, std::strlen(why));
    ::_exit(127);
  }
  ::close(out);
  ::close(err);
  if (pid < 0) error = std::string("fork: ") + std::strerror(errno);
  return pid;
}

}  // namespace

std::vector<JobResult> RunJobs(const std::vector<Job>& jobs, int parallel,
                               const std::function<void(size_t, const JobResult&)>& done) {
  std::vector<JobResult> results(jobs.size());
  std::map<pid_t, std::pair<size_t, Clock::time_point>> running;
  size_t next = 0;
  parallel = std::max(1, parallel);
  while (next < jobs.size() || !running.empty()) {
    while (next < jobs.size() && static_cast<int>(running.size()) < parallel) {
      const size_t i = next++;
      const pid_t pid = Start(jobs[i], results[i].error);
      if (pid < 0) {
        done(i, results[i]);
        continue;
      }
      running[pid] = {i, Clock::now()};
    }
    if (running.empty()) continue;
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;  // no child left that we know of: nothing more to wait for
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    JobResult& r = results[it->second.first];
    r.seconds = std::chrono::duration<double>(Clock::now() - it->second.second).count();
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    const size_t index = it->second.first;
    running.erase(it);
    done(index, r);
  }
  return results;
}

}  // namespace fleetmap::eval::suite
