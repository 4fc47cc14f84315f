#include "drivers/sick/telegram_splitter.h"

#include <gtest/gtest.h>

#include "drivers/sick/commands.h"
#include "drivers/sick/scan_telegram_codec.h"
#include "tests/drivers/sick/sick_test_util.h"

namespace fleetmap::drivers::sick {
namespace {

std::vector<std::string> Drain(TelegramSplitter& s) {
  std::vector<std::string> out;
  while (auto p = s.Next()) out.push_back(*p);
  return out;
}

// Feeds `stream` one byte at a time; the payloads in the order they came out.
std::vector<std::string> FeedByteByByte(TelegramSplitter& s, const std::string& stream) {
  std::vector<std::string> got;
  for (const char c : stream) {
    s.Feed(std::string(1, c));
    for (auto& p : Drain(s)) got.push_back(p);
  }
  return got;
}

TelegramSplitterOptions Options(ColaProtocol p, size_t max = 1 << 20) {
  TelegramSplitterOptions o;
  o.protocol = p;
  o.max_payload_bytes = max;
  return o;
}

class SplitterTest : public ::testing::TestWithParam<ColaProtocol> {};

TEST_P(SplitterTest, ReassemblesTelegramsFedByteByByte) {
  const std::string scan = EncodeScanTelegram(testing::Tim781Like(), GetParam());
  const std::string stream = FrameTelegram(GetParam(), scan) +
                             FrameTelegram(GetParam(), ScanStreamRequest(GetParam(), true)) +
                             FrameTelegram(GetParam(), scan);
  TelegramSplitter s(Options(GetParam()));
  const std::vector<std::string> got = FeedByteByByte(s, stream);
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[0], scan);
  EXPECT_EQ(got[2], scan);
  EXPECT_EQ(s.stats().garbage_bytes, 0u);
  EXPECT_EQ(s.buffered_bytes(), 0u);
}

TEST_P(SplitterTest, SkipsGarbageAndTruncatedTelegrams) {
  const std::string a = ScanStreamRequest(GetParam(), true);
  const std::string framed = FrameTelegram(GetParam(), a);
  std::string stream = "junk\x03\x02\x02 zz" + framed.substr(0, framed.size() / 2) +
                       "\xff\x00 more" + framed + "tail";
  TelegramSplitter s(Options(GetParam()));
  s.Feed(stream);
  const auto got = Drain(s);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], a);
  EXPECT_GT(s.stats().garbage_bytes, 10u);
}

// The same, byte by byte: a telegram cut off by the start of the next one is dropped even
// though the bytes before the new start were already looked at (CoLa-A scans each byte once).
TEST_P(SplitterTest, SkipsATruncatedTelegramFedByteByByte) {
  const std::string a = ScanStreamRequest(GetParam(), true);
  const std::string framed = FrameTelegram(GetParam(), a);
  const std::string stream =
      "junk" + framed.substr(0, framed.size() / 2) + framed + framed.substr(0, 6) + framed;
  TelegramSplitter s(Options(GetParam()));
  const std::vector<std::string> got = FeedByteByByte(s, stream);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], a);
  EXPECT_EQ(got[1], a);
  EXPECT_EQ(s.buffered_bytes(), 0u);
}

INSTANTIATE_TEST_SUITE_P(BothProtocols, SplitterTest,
                         ::testing::Values(ColaProtocol::kColaA, ColaProtocol::kColaB));

TEST(SplitterTest, BadChecksumIsCountedAndTheNextTelegramStillArrives) {
  const std::string good = FrameColaB(ScanPollRequest());
  std::string bad = good;
  bad.back() = static_cast<char>(bad.back() ^ 1);
  TelegramSplitter s(Options(ColaProtocol::kColaB));
  s.Feed(bad + good);
  const auto got = Drain(s);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], ScanPollRequest());
  EXPECT_EQ(s.stats().bad_checksums, 1u);
}

TEST(SplitterTest, FourGigabyteLengthIsRefusedWithoutBuffering) {
  const std::string good = FrameColaB(ScanPollRequest());
  const std::string huge("\x02\x02\x02\x02\xff\xff\xff\xffsRA LMDscandata", 23);
  TelegramSplitter s(Options(ColaProtocol::kColaB));
  s.Feed(huge + good);
  const auto got = Drain(s);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(s.stats().oversized, 1u);
  EXPECT_EQ(s.buffered_bytes(), 0u);
}

TEST(SplitterTest, BufferStaysBoundedOnEndlessGarbage) {
  for (const ColaProtocol p : {ColaProtocol::kColaA, ColaProtocol::kColaB}) {
    TelegramSplitter s(Options(p, 1000));
    // An STX followed by a plausible start and then never an end.
    s.Feed(p == ColaProtocol::kColaA ? std::string("\x02sSN ")
                                     : std::string("\x02\x02\x02\x02\x00\x00\x03\x00sSN ", 13));
    for (int i = 0; i < 200; ++i) {
      s.Feed(std::string(100, 'x'));
      Drain(s);
      EXPECT_LE(s.buffered_bytes(), 1000u + 100u + 13u);
    }
    EXPECT_GT(s.stats().garbage_bytes + s.stats().oversized, 0u) << ColaProtocolName(p);
  }
}

TEST(SplitterTest, BinaryDataThatLooksLikeASyncDoesNotDerail) {
  // LIDinputstate replies contain 02 02 02 02 inside their payload (seen in the LMS111 file).
  const std::string inner("sRA LIDinputstate \x00\x01\x02\x02\x02\x02\x00\x00", 26);
  TelegramSplitter s(Options(ColaProtocol::kColaB));
  s.Feed(FrameColaB(inner) + FrameColaB(ScanPollRequest()));
  const auto got = Drain(s);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0], inner);
}

TEST(CommandsTest, RequestsMatchTheTelegramListing) {
  EXPECT_EQ(FrameColaA(SetAccessModeRequest(ColaProtocol::kColaA)),
            "\x02sMN SetAccessMode 3 F4724744\x03");
  EXPECT_EQ(FrameColaB(SetAccessModeRequest(ColaProtocol::kColaB)),
            std::string(
                "\x02\x02\x02\x02\x00\x00\x00\x17sMN SetAccessMode \x03\xf4\x72\x47\x44\xb3", 32));
  EXPECT_EQ(FrameColaB(ScanStreamRequest(ColaProtocol::kColaB, true)),
            std::string("\x02\x02\x02\x02\x00\x00\x00\x11sEN LMDscandata \x01\x33", 26));
  EXPECT_EQ(FrameColaA(ScanStreamRequest(ColaProtocol::kColaA, false)),
            "\x02sEN LMDscandata 0\x03");
  core::Result<ParsedCommand> c = ParseCommand("sAN SetAccessMode \x01", ColaProtocol::kColaB);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->value, 1u);
  c = ParseCommand(SetAccessModeRequest(ColaProtocol::kColaA), ColaProtocol::kColaA);
  ASSERT_TRUE(c.ok());
  EXPECT_EQ(c->password, kAuthorizedClientPasswordHash);
}

}  // namespace
}  // namespace fleetmap::drivers::sick
