// Numbers typed by an operator (command-line flags): the whole text must be the number.
// std::stoul("-5") wraps to 18446744073709551611 and std::stod("2x") reads 2; both are
// garbage accepted silently, so flags are parsed here instead.
#pragma once

#include <cstdint>
#include <string>

#include "core/result.h"

namespace fleetmap::core {

// A finite decimal number; `what` names it in the error (e.g. "--speed").
Result<double> ParseNumber(const std::string& text, const std::string& what);
// A whole number >= 0, digits only (no sign, no exponent), at most `max`.
Result<uint64_t> ParseCount(const std::string& text, const std::string& what,
                            uint64_t max = UINT64_MAX);

}  // namespace fleetmap::core
