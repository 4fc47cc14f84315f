#include "auth/verifier.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "auth/replay_window.h"
#include "auth/signer.h"
#include "auth/trailer.h"

namespace fleetmap::auth {
namespace {

const std::vector<uint8_t> kPayload = {1, 2, 3, 4, 5, 6, 7, 8, 9};

struct Fleet {
  Key key = GenerateKey();
  Signer v1{key, "v1", 1000};
  Verifier verifier{key};

  std::vector<uint8_t> Signed(Signer& s, const std::string& channel) {
    std::vector<uint8_t> m = kPayload;
    s.Seal(channel, m);
    return m;
  }
  Verdict Open(const std::string& channel, const std::vector<uint8_t>& m,
               const std::string& expected, Opened* out = nullptr) {
    Opened o;
    return verifier.Open(channel, m.data(), static_cast<int>(m.size()), expected, out ? out : &o);
  }
};

TEST(VerifierTest, AcceptsASignedMessageAndReturnsThePayload) {
  Fleet f;
  const auto m = f.Signed(f.v1, "TEMPMAP_v1");
  EXPECT_EQ(m.size(), kPayload.size() + kTrailerFixedBytes + 2);
  Opened o;
  ASSERT_EQ(f.Open("TEMPMAP_v1", m, "v1", &o), Verdict::kAccepted);
  EXPECT_EQ(o.sender, "v1");
  const auto* p = static_cast<const uint8_t*>(o.data);
  EXPECT_EQ(std::vector<uint8_t>(p, p + o.size), kPayload);
  EXPECT_EQ(f.verifier.counters().auth_verified, 1);
}

TEST(VerifierTest, RejectsUnsignedForgedWrongSenderAndReplayed) {
  Fleet f;
  EXPECT_EQ(f.Open("TEMPMAP_v1", kPayload, "v1"), Verdict::kUnsigned);

  Signer stranger(GenerateKey(), "v1", 5000);  // right name, wrong fleet key
  EXPECT_EQ(f.Open("TEMPMAP_v1", f.Signed(stranger, "TEMPMAP_v1"), "v1"), Verdict::kForged);

  auto altered = f.Signed(f.v1, "TEMPMAP_v1");
  altered[3] ^= 1;
  EXPECT_EQ(f.Open("TEMPMAP_v1", altered, "v1"), Verdict::kForged);
  // Moved to another channel: the MAC covers the channel name.
  EXPECT_EQ(f.Open("TEMPMAP_v2", f.Signed(f.v1, "TEMPMAP_v1"), ""), Verdict::kForged);

  Signer v2(f.key, "v2", 1000);  // a real member, on another member's channel
  EXPECT_EQ(f.Open("TEMPMAP_v1", f.Signed(v2, "TEMPMAP_v1"), "v1"), Verdict::kWrongSender);

  const auto once = f.Signed(f.v1, "TEMPMAP_v1");
  EXPECT_EQ(f.Open("TEMPMAP_v1", once, "v1"), Verdict::kAccepted);
  EXPECT_EQ(f.Open("TEMPMAP_v1", once, "v1"), Verdict::kReplayed);

  const AuthCounters& c = f.verifier.counters();
  EXPECT_EQ(c.auth_unsigned, 1);
  EXPECT_EQ(c.auth_forged, 3);
  EXPECT_EQ(c.auth_wrong_sender, 1);
  EXPECT_EQ(c.auth_replayed, 1);
  EXPECT_EQ(c.auth_verified, 1);
}

TEST(VerifierTest, EverySingleBitFlipIsRefused) {
  Fleet f;
  const auto m = f.Signed(f.v1, "MAP_REQUEST");
  for (size_t i = 0; i < m.size() * 8; ++i) {
    auto flipped = m;
    flipped[i / 8] ^= static_cast<uint8_t>(1u << (i % 8));
    EXPECT_NE(f.Open("MAP_REQUEST", flipped, ""), Verdict::kAccepted) << "bit " << i;
  }
  EXPECT_EQ(f.Open("MAP_REQUEST", m, ""), Verdict::kAccepted);
  std::printf("%zu single-bit flips refused\n", m.size() * 8);
}

TEST(VerifierTest, WithoutAKeyATrailerIsSplitOffAndAnythingPasses) {
  Fleet f;
  Verifier open_fleet;
  Opened o;
  const auto m = f.Signed(f.v1, "TEMPMAP_v1");
  ASSERT_EQ(open_fleet.Open("TEMPMAP_v1", m.data(), static_cast<int>(m.size()), "v1", &o),
            Verdict::kAccepted);
  EXPECT_EQ(o.size, static_cast<int>(kPayload.size()));
  ASSERT_EQ(open_fleet.Open("X", kPayload.data(), static_cast<int>(kPayload.size()), "", &o),
            Verdict::kAccepted);
  EXPECT_EQ(o.size, static_cast<int>(kPayload.size()));
  EXPECT_EQ(open_fleet.counters().auth_unverified, 1);
  EXPECT_FALSE(open_fleet.enabled());

  Signer none;  // no key and no name: nothing appended
  std::vector<uint8_t> plain = kPayload;
  none.Seal("X", plain);
  EXPECT_EQ(plain, kPayload);
}

// Without a key a process still names itself and numbers its messages (an identity trailer):
// a reader can tell who sent what, and a keyed receiver takes it for unsigned.
TEST(VerifierTest, WithoutAKeyASenderNamesItselfAndAKeyedFleetTakesThatForUnsigned) {
  Signer named(std::nullopt, "aggregator", 77);
  std::vector<uint8_t> m = kPayload;
  named.Seal("MAP_DELTA", m);
  EXPECT_EQ(m.size(), kPayload.size() + kIdentityTrailerFixedBytes + 10);
  Trailer t;
  ASSERT_TRUE(SplitTrailer(m.data(), m.size(), &t));
  EXPECT_FALSE(t.has_mac());
  EXPECT_EQ(t.sender, "aggregator");
  EXPECT_EQ(t.seq, 77u);
  EXPECT_EQ(t.payload_size, kPayload.size());
  EXPECT_EQ(PayloadSize(m.data(), m.size()), kPayload.size());
  EXPECT_EQ(PayloadSize(kPayload.data(), kPayload.size()), kPayload.size());
  named.Seal("MAP_DELTA", m = kPayload);
  ASSERT_TRUE(SplitTrailer(m.data(), m.size(), &t));
  EXPECT_EQ(t.seq, 78u);  // one more per message

  Verifier open_fleet;
  Opened o;
  ASSERT_EQ(open_fleet.Open("MAP_DELTA", m.data(), static_cast<int>(m.size()), "", &o),
            Verdict::kAccepted);
  EXPECT_EQ(o.size, static_cast<int>(kPayload.size()));

  Fleet f;
  EXPECT_FALSE(MacMatches("MAP_DELTA", t, f.key));
  EXPECT_EQ(f.Open("MAP_DELTA", m, "aggregator"), Verdict::kUnsigned);
  EXPECT_EQ(f.verifier.counters().auth_unsigned, 1);
}

TEST(VerifierTest, ARestartedSenderStartsAboveWhereItStopped) {
  Fleet f;
  Signer first(f.key, "v1", FirstSequence(1.7e9));
  for (int i = 0; i < 5000; ++i)
    ASSERT_EQ(f.Open("POSE_v1", f.Signed(first, "POSE_v1"), "v1"), Verdict::kAccepted);
  Signer restarted(f.key, "v1", FirstSequence(1.7e9 + 0.001));
  EXPECT_EQ(f.Open("POSE_v1", f.Signed(restarted, "POSE_v1"), "v1"), Verdict::kAccepted);
  Signer clock_went_back(f.key, "v1", FirstSequence(1.7e9 - 1));
  EXPECT_EQ(f.Open("POSE_v1", f.Signed(clock_went_back, "POSE_v1"), "v1"), Verdict::kReplayed);
}

TEST(ReplayWindowTest, AcceptsGapsAndReorderingWithinTheWindowOnlyOnce) {
  ReplayWindow w;
  EXPECT_TRUE(w.Accept(100));
  EXPECT_TRUE(w.Accept(105));
  EXPECT_TRUE(w.Accept(103));  // late but new
  EXPECT_FALSE(w.Accept(103));
  EXPECT_FALSE(w.Accept(105));
  EXPECT_TRUE(w.Accept(100 + ReplayWindow::kWindow + 50));
  EXPECT_FALSE(w.Accept(101));  // now below the window
  EXPECT_TRUE(w.Accept(100 + ReplayWindow::kWindow + 49));
  EXPECT_EQ(w.highest(), 100 + ReplayWindow::kWindow + 50);
}

TEST(TrailerTest, SplitRefusesWhatIsNoTrailer) {
  Trailer t;
  EXPECT_FALSE(SplitTrailer(kPayload.data(), kPayload.size(), &t));
  std::vector<uint8_t> fake(100, 0);
  fake[96] = 'F';
  fake[97] = 'M';
  fake[98] = 'A';
  fake[99] = '1';
  EXPECT_FALSE(SplitTrailer(fake.data(), fake.size(), &t));  // sender length 0
  fake[100 - 4 - 32 - 8 - 1] = 200;                          // longer than allowed
  EXPECT_FALSE(SplitTrailer(fake.data(), fake.size(), &t));
  EXPECT_FALSE(SplitTrailer(nullptr, 0, &t));
  std::vector<uint8_t> short_identity = {0, 0, 0, 0, 0, 0, 0, 0, 0, 'F', 'M', 'I', '1'};
  EXPECT_FALSE(SplitTrailer(short_identity.data(), short_identity.size(), &t));
  short_identity.insert(short_identity.begin(), 'x');
  short_identity[1] = 2;  // a sender of 2 bytes, but only 1 before it
  EXPECT_FALSE(SplitTrailer(short_identity.data(), short_identity.size(), &t));
  short_identity[1] = 1;
  EXPECT_TRUE(SplitTrailer(short_identity.data(), short_identity.size(), &t));
  EXPECT_EQ(t.sender, "x");
  EXPECT_EQ(t.payload_size, 0u);
}

}  // namespace
}  // namespace fleetmap::auth
