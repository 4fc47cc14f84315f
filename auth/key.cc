#include "auth/key.h"

#include <sodium.h>
#include <sys/stat.h>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fleetmap::auth {
namespace {

constexpr const char* kDeriveDomain = "fleetmap sender key v1";

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

void InitSodium() {
  if (sodium_init() < 0) std::abort();  // no usable random source: nothing is safe to do
}

Key::~Key() { sodium_memzero(bytes_.data(), bytes_.size()); }

core::Result<Key> ParseKeyText(const std::string& text) {
  std::string hex;
  for (char c : text)
    if (!std::isspace(static_cast<unsigned char>(c))) hex.push_back(c);
  if (hex.size() != 2 * kKeyBytes) {
    return core::InvalidArgument("a key is 64 hexadecimal digits (32 bytes), found " +
                                 std::to_string(hex.size()) + " characters");
  }
  std::array<uint8_t, kKeyBytes> bytes{};
  for (size_t i = 0; i < kKeyBytes; ++i) {
    const int hi = HexDigit(hex[2 * i]);
    const int lo = HexDigit(hex[2 * i + 1]);
    if (hi < 0 || lo < 0) return core::InvalidArgument("a key holds hexadecimal digits only");
    bytes[i] = static_cast<uint8_t>(hi * 16 + lo);
  }
  Key key(bytes);
  sodium_memzero(bytes.data(), bytes.size());
  return key;
}

core::Result<Key> ReadKeyFile(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0) return core::NotFound("key file " + path + ": cannot stat it");
  if (!S_ISREG(st.st_mode)) return core::InvalidArgument("key file " + path + ": not a file");
  if ((st.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    std::ostringstream mode;
    mode << std::oct << (st.st_mode & 0777);
    return core::FailedPrecondition("key file " + path + " has mode " + mode.str() +
                                    ": its group or others may read or change it; refusing it "
                                    "(run: chmod 600 " +
                                    path + ")");
  }
  std::ifstream in(path);
  if (!in) return core::IoError("key file " + path + ": cannot read it");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  auto key = ParseKeyText(s);
  sodium_memzero(s.data(), s.size());
  if (!key.ok()) return key.status().WithContext("key file " + path);
  return key;
}

std::string KeyToHex(const Key& key) {
  static const char* kDigits = "0123456789abcdef";
  std::string hex;
  for (size_t i = 0; i < kKeyBytes; ++i) {
    hex.push_back(kDigits[key.data()[i] >> 4]);
    hex.push_back(kDigits[key.data()[i] & 15]);
  }
  return hex;
}

Key GenerateKey() {
  std::array<uint8_t, kKeyBytes> bytes{};
  InitSodium();
  randombytes_buf(bytes.data(), bytes.size());
  Key key(bytes);
  sodium_memzero(bytes.data(), bytes.size());
  return key;
}

Key DeriveSenderKey(const Key& fleet_key, const std::string& sender) {
  std::string input = kDeriveDomain;
  input.push_back('\0');
  input += sender;
  InitSodium();
  std::array<uint8_t, kKeyBytes> out{};
  crypto_generichash(out.data(), out.size(), reinterpret_cast<const uint8_t*>(input.data()),
                     input.size(), fleet_key.data(), kKeyBytes);
  Key key(out);
  sodium_memzero(out.data(), out.size());
  return key;
}

}  // namespace fleetmap::auth
