// fleetmap-record: records LCM traffic into an LCM log file, like lcm-logger, but without
// losing messages when the machine is busy. LCM keeps at most 30 received messages per
// subscription and silently drops the rest; lcm-logger sets no other capacity, so a burst of
// map tiles while its thread waits for the CPU loses some of them, and a log that lacks one
// tile cannot be replayed into the same map. This recorder asks for a deep queue, checks
// every write (a full disk is an error, not a short log) and flushes once a second.
#include <sys/stat.h>
#include <time.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <optional>
#include <string>

#include "core/command_line.h"

namespace {

volatile std::sig_atomic_t g_stop = 0;
void OnSignal(int) { g_stop = 1; }

struct Options {
  std::string url;
  std::string channel = ".*";
  int queue_messages = 100000;
  bool force = false;
  bool quiet = false;
  std::string path;
};

// Reads the command line into `o`. No value: go on; otherwise the exit status.
std::optional<int> ParseArgs(int argc, char** argv, Options& o) {
  CLI::App app(
      "Records every message of one LCM group whose channel matches REGEX into FILE.lcmlog\n"
      "(the format of lcm-logger, readable by lcm-logplayer, fleetmap-eval and\n"
      "fleetmap-aggregator --replay). Stop it with SIGINT or SIGTERM; it then closes the file\n"
      "and prints a summary.\n"
      "Exit status: 0 after a clean stop, 1 on a write error (disk full...), 2 on usage errors.",
      "fleetmap-record");
  fleetmap::core::AddVersionFlag(app);
  app.add_option("--lcm-url", o.url, "the group to record (default: LCM's)");
  app.add_option("--channel", o.channel, "channels to record (a regex)")->capture_default_str();
  app.add_option("--queue", o.queue_messages,
                 "messages LCM may hold for the recorder while it writes")
      ->check(CLI::Range(1, 10000000))
      ->capture_default_str();
  app.add_flag("-f,--force", o.force, "overwrite FILE if it exists");
  app.add_flag("-q,--quiet", o.quiet, "no progress lines (every 10 s otherwise)");
  app.add_option("FILE.lcmlog", o.path, "the log to write")->required();
  return fleetmap::core::ParseCommandLine(app, argc, argv);
}

double MonotonicSeconds() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

class Recorder {
 public:
  explicit Recorder(lcm::LogFile* log) : log_(log) {}

  void OnMessage(const lcm::ReceiveBuffer* rbuf, const std::string& channel) {
    if (failed_) return;
    // The receive stamps LCM gives can step back by milliseconds under load; a log's stamps
    // must not (players sleep by their differences, replays order by them).
    last_stamp_ = std::max(last_stamp_, rbuf->recv_utime);
    lcm::LogEvent ev{};
    ev.timestamp = last_stamp_;
    ev.channel = channel;
    ev.datalen = static_cast<int32_t>(rbuf->data_size);
    ev.data = rbuf->data;
    if (log_->writeEvent(&ev) != 0) {
      failed_ = true;
      error_ = std::strerror(errno);
      return;
    }
    ++events_;
    bytes_ += rbuf->data_size;
  }
  // Flushes to the kernel so that a crash of this process loses at most a second.
  void Flush() {
    if (!failed_ && std::fflush(log_->getFilePtr()) != 0) {
      failed_ = true;
      error_ = std::strerror(errno);
    }
  }
  bool failed() const { return failed_; }
  const std::string& error() const { return error_; }
  long long events() const { return events_; }
  long long bytes() const { return bytes_; }

 private:
  lcm::LogFile* log_;
  bool failed_ = false;
  std::string error_;
  long long events_ = 0;
  long long bytes_ = 0;
  int64_t last_stamp_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (const auto exit_status = ParseArgs(argc, argv, o)) return *exit_status;
  struct stat st {};
  if (!o.force && stat(o.path.c_str(), &st) == 0) {
    std::fprintf(stderr, "fleetmap-record: %s exists (--force overwrites it)\n", o.path.c_str());
    return 2;
  }
  lcm::LogFile log(o.path, "w");
  if (!log.good()) {
    std::fprintf(stderr, "fleetmap-record: cannot write %s: %s\n", o.path.c_str(),
                 std::strerror(errno));
    return 1;
  }
  lcm::LCM lcm(o.url);
  if (!lcm.good()) {
    std::fprintf(stderr,
                 "fleetmap-record: cannot open LCM at '%s' (multicast route? see "
                 "scripts/setup_multicast.sh)\n",
                 o.url.c_str());
    return 1;
  }
  Recorder recorder(&log);
  lcm::Subscription* sub = lcm.subscribe(o.channel, &Recorder::OnMessage, &recorder);
  sub->setQueueCapacity(o.queue_messages);
  std::signal(SIGINT, OnSignal);
  std::signal(SIGTERM, OnSignal);

  double last_flush = MonotonicSeconds();
  double last_progress = last_flush;
  while (!g_stop && !recorder.failed()) {
    // A signal interrupts the wait (EINTR): that is a stop, not a failure.
    if (lcm.handleTimeout(100) < 0 && !g_stop) {
      std::fprintf(stderr, "fleetmap-record: LCM failed while receiving\n");
      return 1;
    }
    const double now = MonotonicSeconds();
    if (now - last_flush >= 1.0) {
      recorder.Flush();
      last_flush = now;
    }
    if (!o.quiet && now - last_progress >= 10.0) {
      std::fprintf(stderr, "fleetmap-record: %lld messages, %.1f MB\n", recorder.events(),
                   static_cast<double>(recorder.bytes()) / 1e6);
      last_progress = now;
    }
  }
  // Whatever LCM still holds for us was received before the stop: write it too.
  while (!recorder.failed() && lcm.handleTimeout(0) > 0) {
  }
  recorder.Flush();
  if (recorder.failed()) {
    std::fprintf(stderr,
                 "fleetmap-record: writing %s failed: %s; the log holds the first %lld "
                 "messages\n",
                 o.path.c_str(), recorder.error().c_str(), recorder.events());
    return 1;
  }
  std::printf("fleetmap-record: %s: %lld messages, %lld bytes\n", o.path.c_str(), recorder.events(),
              recorder.bytes());
  return 0;
}
