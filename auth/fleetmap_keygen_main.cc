// fleetmap-keygen FILE: writes a new random fleet key (docs/security.md) to FILE, readable
// by its owner only, and refuses to overwrite an existing file.
#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "auth/key.h"
#include "core/version.h"

int main(int argc, char** argv) {
  // A key file cannot be named --version: asking for the version writes no key.
  if (fleetmap::core::PrintVersionIfAsked(argc, argv, "fleetmap-keygen")) return 0;
  if (argc != 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
    std::fprintf(argc == 2 ? stdout : stderr,
                 "usage: fleetmap-keygen FILE\n"
                 "Writes a new random fleet key (64 hex digits) to FILE with mode 600; every\n"
                 "fleetmap-agent and fleetmap-aggregator of the fleet takes it as --key-file.\n"
                 "An existing FILE is never overwritten.\n");
    return argc == 2 ? 0 : 2;
  }
  const int fd = ::open(argv[1], O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    std::fprintf(stderr, "fleetmap-keygen: %s: %s\n", argv[1], std::strerror(errno));
    return 1;
  }
  const std::string text = fleetmap::auth::KeyToHex(fleetmap::auth::GenerateKey()) + "\n";
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size());
  if (::close(fd) != 0 || !ok) {
    std::fprintf(stderr, "fleetmap-keygen: %s: cannot write the key\n", argv[1]);
    return 1;
  }
  return 0;
}
