// fleetmap-keygen FILE: writes a new random fleet key (docs/security.md) to FILE, readable
// by its owner only, and refuses to overwrite an existing file.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "auth/key.h"
#include "core/command_line.h"

int main(int argc, char** argv) {
  CLI::App app(
      "Writes a new random fleet key (64 hex digits) to FILE with mode 600; every\n"
      "fleetmap-agent and fleetmap-aggregator of the fleet takes it as --key-file.\n"
      "An existing FILE is never overwritten.\n"
      "Exit status: 0 written, 1 the file exists or cannot be written, 2 usage errors.",
      "fleetmap-keygen");
  fleetmap::core::AddVersionFlag(app);  // asking for the version writes no key
  std::string path;
  app.add_option("FILE", path, "the key file to create")->required();
  if (const auto exit_status = fleetmap::core::ParseCommandLine(app, argc, argv))
    return *exit_status;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    std::fprintf(stderr, "fleetmap-keygen: %s: %s\n", path.c_str(), std::strerror(errno));
    return 1;
  }
  const std::string text = fleetmap::auth::KeyToHex(fleetmap::auth::GenerateKey()) + "\n";
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  if (::close(fd) != 0 || !ok) {
    std::fprintf(stderr, "fleetmap-keygen: %s: cannot write the key\n", path.c_str());
    return 1;
  }
  return 0;
}
