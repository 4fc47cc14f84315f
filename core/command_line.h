// Every program reads its command line the same way: CLI11 (Debian's libcli11-dev), --help
// and --version alike everywhere, a bad value named with its flag. Target
// fleetmap_command_line: this header alone, for programs that need nothing else of core.
//
//   CLI::App app("What the program does.", "fleetmap-x");
//   core::AddVersionFlag(app);
//   app.add_option("--period", period_s, "seconds between ...")->capture_default_str();
//   if (const auto exit_status = core::ParseCommandLine(app, argc, argv)) return *exit_status;
#pragma once

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "core/version.h"

namespace fleetmap::core {

// --version prints "<program> <version>", the program being the app's name.
inline void AddVersionFlag(CLI::App& app) {
  app.set_version_flag("--version", app.get_name() + " " + kFleetmapVersion);
}

// A check for a number flag: CLI11 refuses "60s", "3.5" for a whole number and "-5" for an
// unsigned one, but reads "nan" and "inf" as doubles.
inline CLI::Validator Finite() {
  return CLI::Validator(
      [](std::string& text) {
        double value = 0.0;
        return CLI::detail::lexical_cast(text, value) && std::isfinite(value)
                   ? std::string()
                   : "not a finite number: " + text;
      },
      "", "finite");
}

// A check for a number flag that must be finite and above 0 (a period, a resolution).
inline CLI::Validator Positive() {
  return CLI::Validator(
      [](std::string& text) {
        double value = 0.0;
        return CLI::detail::lexical_cast(text, value) && std::isfinite(value) && value > 0
                   ? std::string()
                   : "not a number above 0: " + text;
      },
      "", "positive");
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
