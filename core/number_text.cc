#include "core/number_text.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

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

double NumberOrThrow(const std::string& text, const std::string& what) {
  Result<double> v = ParseNumber(text, what);
  if (!v.ok()) throw std::invalid_argument(v.status().message());
  return *v;
}

int IntegerOrThrow(const std::string& text, const std::string& what) {
  const bool negative = !text.empty() && text[0] == '-';
  Result<uint64_t> v = ParseCount(negative ? text.substr(1) : text, what, 1u << 30);
  if (!v.ok()) throw std::invalid_argument(what + ": not a whole number: '" + text + "'");
  return negative ? -static_cast<int>(*v) : static_cast<int>(*v);
}

}  // namespace fleetmap::core
