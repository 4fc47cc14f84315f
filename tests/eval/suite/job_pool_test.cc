#include "eval/suite/job_pool.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <sstream>

namespace fleetmap::eval::suite {
namespace {

std::string Path(const std::string& name) {
  return ::testing::TempDir() + "job_pool_" + name + std::to_string(getpid());
}

std::string Read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

Job Shell(const std::string& name, const std::string& script) {
  return {{"/bin/sh", "-c", script}, Path(name + ".out"), Path(name + ".err")};
}

TEST(JobPoolTest, RunsEveryJobWithItsOutputAndStatus) {
  const std::vector<Job> jobs = {Shell("a", "echo one"), Shell("b", "echo two >&2; exit 3"),
                                 Shell("c", "kill -9 $$"), Shell("d", "echo four")};
  std::vector<size_t> done;
  const std::vector<JobResult> r =
      RunJobs(jobs, 2, [&](size_t i, const JobResult&) { done.push_back(i); });
  ASSERT_EQ(r.size(), 4u);
  EXPECT_EQ(r[0].exit_code, 0);
  EXPECT_EQ(Read(jobs[0].stdout_path), "one\n");
  EXPECT_EQ(r[1].exit_code, 3);
  EXPECT_EQ(Read(jobs[1].stderr_path), "two\n");
  EXPECT_EQ(r[2].exit_code, 128 + 9);
  EXPECT_EQ(Read(jobs[3].stdout_path), "four\n");
  EXPECT_EQ(done.size(), 4u);
}

TEST(JobPoolTest, AProgramThatCannotRunIsReportedAndTheOthersStillRun) {
  const std::vector<Job> jobs = {{{"/no/such/program"}, Path("x.out"), Path("x.err")},
                                 {{"/bin/sh", "-c", "true"}, "/no/such/folder/out", Path("y.err")},
                                 Shell("z", "true")};
  const std::vector<JobResult> r = RunJobs(jobs, 1, [](size_t, const JobResult&) {});
  EXPECT_EQ(r[0].exit_code, 127);
  EXPECT_NE(Read(jobs[0].stderr_path).find("cannot run the program"), std::string::npos);
  EXPECT_EQ(r[1].exit_code, -1);
  EXPECT_NE(r[1].error.find("cannot open the output files"), std::string::npos);
  EXPECT_EQ(r[2].exit_code, 0);
}

}  // namespace
}  // namespace fleetmap::eval::suite
