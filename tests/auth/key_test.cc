#include "auth/key.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace fleetmap::auth {
namespace {

const char* kHex = "000102030405060708090a0b0c0d0e0f101112131415161718191a1b1c1d1e1f";

std::string WriteFile(const std::string& text, mode_t mode) {
  std::string path = (std::filesystem::temp_directory_path() / "fleetmap_key_XXXXXX").string();
  const int fd = mkstemp(path.data());
  EXPECT_GE(fd, 0);
  close(fd);
  std::ofstream(path) << text;
  chmod(path.c_str(), mode);
  return path;
}

TEST(KeyTest, ParsesHexWithWhitespace) {
  auto key = ParseKeyText(std::string(" ") + kHex + "\n");
  ASSERT_TRUE(key.ok()) << key.status().ToString();
  EXPECT_EQ(key->data()[0], 0);
  EXPECT_EQ(key->data()[31], 31);
  EXPECT_EQ(KeyToHex(*key), kHex);
}

TEST(KeyTest, RefusesWrongLengthAndNonHex) {
  EXPECT_FALSE(ParseKeyText("abcd").ok());
  std::string bad = kHex;
  bad[5] = 'x';
  EXPECT_FALSE(ParseKeyText(bad).ok());
}

TEST(KeyTest, ReadsAFileOnlyItsOwnerCanRead) {
  const std::string path = WriteFile(kHex, 0600);
  auto key = ReadKeyFile(path);
  ASSERT_TRUE(key.ok()) << key.status().ToString();
  EXPECT_EQ(KeyToHex(*key), kHex);
  std::filesystem::remove(path);
}

TEST(KeyTest, RefusesAGroupOrWorldReadableFileAndSaysHowToFixIt) {
  for (mode_t mode : {0644, 0640, 0604, 0660}) {
    const std::string path = WriteFile(kHex, mode);
    auto key = ReadKeyFile(path);
    ASSERT_FALSE(key.ok()) << std::oct << mode;
    EXPECT_EQ(key.status().code(), core::StatusCode::kFailedPrecondition);
    EXPECT_NE(key.status().message().find("chmod 600"), std::string::npos)
        << key.status().message();
    std::filesystem::remove(path);
  }
}

TEST(KeyTest, MissingFileAndFolderAreErrors) {
  EXPECT_EQ(ReadKeyFile("/nonexistent/fleet.key").status().code(), core::StatusCode::kNotFound);
  EXPECT_FALSE(ReadKeyFile("/tmp").ok());
}

TEST(KeyTest, SenderKeysDifferPerSenderAndPerFleet) {
  const Key fleet = *ParseKeyText(kHex);
  const Key other = GenerateKey();
  const std::string a = KeyToHex(DeriveSenderKey(fleet, "v1"));
  EXPECT_EQ(a, KeyToHex(DeriveSenderKey(fleet, "v1")));
  EXPECT_NE(a, KeyToHex(DeriveSenderKey(fleet, "v2")));
  EXPECT_NE(a, KeyToHex(DeriveSenderKey(other, "v1")));
  EXPECT_NE(a, KeyToHex(fleet));
}

}  // namespace
}  // namespace fleetmap::auth
