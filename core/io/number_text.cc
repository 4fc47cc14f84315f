#include "core/io/number_text.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace fleetmap::core {

Result<double> ParseNumber(const std::string& text, const std::string& what) {
  char* end = nullptr;
  errno = 0;
  const double v = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    return InvalidArgument(what + ": not a number: '" + text + "'");
  return v;
}

Result<uint64_t> ParseCount(const std::string& text, const std::string& what, uint64_t max) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    return InvalidArgument(what + ": not a whole number >= 0: '" + text + "'");
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE || v > max)
    return InvalidArgument(what + ": " + text + " is above " + std::to_string(max));
  return static_cast<uint64_t>(v);
}

}  // namespace fleetmap::core
