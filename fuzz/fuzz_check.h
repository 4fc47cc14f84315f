// Property checks inside fuzz targets. A decoder that returns an error is fine; a decoder that
// accepts an input and then disagrees with itself (a round trip that changes the value, a
// grid left half-written) is a bug even when nothing crashed, so the target aborts and
// libFuzzer saves the input like any crash.
#pragma once

#include <cstdio>
#include <cstdlib>

namespace fleetmap::fuzz {

[[noreturn]] inline void PropertyFailed(const char* what, const char* file, int line) {
  std::fprintf(stderr, "%s:%d: fuzz property violated: %s\n", file, line, what);
  std::abort();
}

}  // namespace fleetmap::fuzz

// Aborts with the condition's text when it is false. Not assert(): it must hold in every build.
#define FUZZ_REQUIRE(condition) \
  ((condition) ? (void)0 : ::fleetmap::fuzz::PropertyFailed(#condition, __FILE__, __LINE__))
