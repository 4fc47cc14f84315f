// Runs programs, a few at a time, each with its output in files: the suite's evaluations are
// separate processes, so that one world that crashes or runs out of memory costs only itself.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace fleetmap::eval::suite {

struct Job {
  std::vector<std::string> argv;  // argv[0]: the program's path
  std::string stdout_path, stderr_path;
};

struct JobResult {
  int exit_code = -1;    // the program's status; 128 + N when killed by signal N; -1: not started
  double seconds = 0.0;  // wall clock
  std::string error;     // why it could not be started
};

// Runs every job, at most `parallel` at once, in order of the list. `done` is called (on this
// thread) as each ends, with its index.
std::vector<JobResult> RunJobs(const std::vector<Job>& jobs, int parallel,
                               const std::function<void(size_t, const JobResult&)>& done);

}  // namespace fleetmap::eval::suite
