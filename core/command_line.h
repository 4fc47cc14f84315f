// Every program reads its command line the same way: CLI11 (Debian's libcli11-dev), --help
// and --version alike everywhere, a bad value named with its flag. Target
// fleetmap_command_line (this header and core's number parsing).
//
//   CLI::App app("What the program does.", "fleetmap-x");
//   core::AddVersionFlag(app);
//   app.add_option("--period", period_s, "seconds between ...")->capture_default_str();
//   if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <string>

#include "core/io/number_text.h"
#include "core/version.h"

namespace fleetmap::core {

// --version prints "<program> <version>", the program being the app's name.
inline void AddVersionFlag(CLI::App& app) {
  app.set_version_flag("--version", app.get_name() + " " + kFleetmapVersion);
}

// Checks for number flags, worded as core::ParseNumber words them (the whole text a finite
// number). CLI11 itself refuses "60s" and "3.5" for a whole number, but reads "nan" and "inf"
// as doubles.
enum class NumberRange { kAny, kNotNegative, kPositive };
inline CLI::Validator NumberCheck(NumberRange range) {
  return CLI::Validator(
      [range](std::string& text) {
        const Result<double> value = ParseNumber(text, "value");
        if (!value.ok()) return value.status().message();
        if (range == NumberRange::kPositive && !(*value > 0))
          return "value: not above 0: '" + text + "'";
        if (range == NumberRange::kNotNegative && *value < 0)
          return "value: below 0: '" + text + "'";
        return std::string();
      },
      "",
      range == NumberRange::kAny        ? "finite"
      : range == NumberRange::kPositive ? "positive"
                                        : ">= 0");
}
inline CLI::Validator Finite() { return NumberCheck(NumberRange::kAny); }
// A duration, a count of seconds to wait: finite and not below 0.
inline CLI::Validator NotNegative() { return NumberCheck(NumberRange::kNotNegative); }
// A period, a resolution: finite and above 0.
inline CLI::Validator Positive() { return NumberCheck(NumberRange::kPositive); }

// A count, a version, a seed: digits only. CLI11 2.1 reads "-2" into an unsigned variable as
// 2^64 - 2.
inline CLI::Validator WholeNumber() {
  return CLI::Validator(
      [](std::string& text) {
        const Result<uint64_t> value = ParseCount(text, "value");
        return value.ok() ? std::string() : value.status().message();
      },
      "", "whole number");
}

// Parses the command line into `app`. No value: go on. Otherwise the exit status: 0 after
// --help or --version (printed on stdout), 2 after a usage error, printed on stderr as
// "<program>: <what was wrong> (see --help)".
inline std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s (see --help)\n", app.get_name().c_str(), e.what());
    return 2;
  }
  return std::nullopt;
}

}  // namespace fleetmap::core
