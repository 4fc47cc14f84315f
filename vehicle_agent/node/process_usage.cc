#include "vehicle_agent/node/process_usage.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>

namespace fleetmap::vehicle_agent::node {
namespace {

int64_t Microseconds(const timeval& t) {
  return static_cast<int64_t>(t.tv_sec) * 1000000 + static_cast<int64_t>(t.tv_usec);
}

// The resident set now (ru_maxrss would be the peak): the second field of /proc/self/statm,
// in pages. -1 where there is no /proc.
int64_t ResidentKilobytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return -1;
  long long size_pages = 0, resident_pages = 0;
  const int n = std::fscanf(f, "%lld %lld", &size_pages, &resident_pages);
  std::fclose(f);
  const long page_bytes = sysconf(_SC_PAGESIZE);
  if (n != 2 || page_bytes <= 0) return -1;
  return resident_pages * page_bytes / 1024;
}

}  // namespace

NamedCounters ProcessUsageCounters() {
  NamedCounters out;
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0)
    out.emplace_back("cpu_time_us", Microseconds(usage.ru_utime) + Microseconds(usage.ru_stime));
  const int64_t rss_kb = ResidentKilobytes();
  if (rss_kb >= 0) out.emplace_back("rss_kb", rss_kb);
  return out;
}

}  // namespace fleetmap::vehicle_agent::node
