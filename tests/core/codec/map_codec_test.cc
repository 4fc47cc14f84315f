#include "core/codec/map_codec.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zstd.h>

#include <random>

#include "core/io/byte_io.h"
#include "core/io/crc32.h"

namespace fleetmap::core {
namespace {

using ::testing::HasSubstr;

OccupancyGrid RandomGrid(int w, int h, unsigned seed) {
  OccupancyGrid grid(GridGeometry(0.05, w, h));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> l(-5.0f, 5.0f);
  for (float& c : grid.mutable_cells()) c = std::clamp(l(rng), -4.6f, 4.6f);
  return grid;
}

// Re-computes the trailing CRC after a deliberate edit, so that a test reaches the check
// behind the CRC.
void FixCrc(std::vector<uint8_t>& frame) {
  frame.resize(frame.size() - 4);
  ByteWriter(frame).U32(Crc32(frame.data(), frame.size()));
}

void PutU32(std::vector<uint8_t>& f, size_t offset, uint32_t v) {
  for (int i = 0; i < 4; ++i) f[offset + i] = static_cast<uint8_t>(v >> (8 * i));
}

class MapCodecRoundTrip : public ::testing::TestWithParam<std::tuple<CellPacking, Compression>> {};

TEST_P(MapCodecRoundTrip, WindowSurvives) {
  const auto [packing, compression] = GetParam();
  const OccupancyGrid grid = RandomGrid(70, 45, 1);
  const CellWindow window{5, 7, 61, 33};  // odd sizes exercise 2-bit padding
  CodecOptions options;
  options.packing = packing;
  options.compression = compression;
  const auto frame = EncodeWindow(grid, window, options);
  auto decoded = DecodeFrame(frame);
  ASSERT_TRUE(decoded.ok()) << decoded.status().ToString();
  EXPECT_EQ(decoded->window, window);
  EXPECT_EQ(decoded->packing, packing);
  OccupancyGrid copy(grid.geometry());
  ASSERT_TRUE(ApplyFrame(*decoded, copy).ok());
  for (int y = window.y0; y < window.y0 + window.height; ++y) {
    for (int x = window.x0; x < window.x0 + window.width; ++x) {
      if (packing == CellPacking::kLogOddsInt8) {
        ASSERT_NEAR(copy.log_odds({x, y}), grid.log_odds({x, y}), kLogOddsQuantum / 2 + 1e-6);
      } else {
        ASSERT_EQ(copy.state({x, y}), grid.state({x, y})) << x << "," << y;
      }
    }
  }
  EXPECT_EQ(copy.state({0, 0}), CellState::kUnknown);  // outside the window: untouched
}

INSTANTIATE_TEST_SUITE_P(
    AllPackings, MapCodecRoundTrip,
    ::testing::Combine(::testing::Values(CellPacking::kTriState2Bit, CellPacking::kTriState8Bit,
                                         CellPacking::kLogOddsInt8),
                       ::testing::Values(Compression::kNone, Compression::kZstd,
                                         Compression::kZlib)),
    [](const auto& info) {
      return std::string(CellPackingName(std::get<0>(info.param))) + "_" +
             CompressionName(std::get<1>(info.param));
    });

class MapCodecCorruption : public ::testing::Test {
 protected:
  void SetUp() override {
    grid_ = RandomGrid(64, 64, 2);
    frame_ = EncodeWindow(grid_, grid_.geometry().full_window());
  }
  Status Decode(const std::vector<uint8_t>& f, DecodeLimits limits = {}) {
    return DecodeFrame(f, limits).status();
  }
  OccupancyGrid grid_;
  std::vector<uint8_t> frame_;
};

TEST_F(MapCodecCorruption, FlippedPayloadBitFailsTheCrc) {
  frame_[kCodecHeaderBytes + 3] ^= 0x10;
  const Status s = Decode(frame_);
  EXPECT_EQ(s.code(), StatusCode::kDataLoss);
  EXPECT_THAT(s.message(), HasSubstr("CRC"));
}

TEST_F(MapCodecCorruption, WrongVersionIsUnimplemented) {
  frame_[4] = kCodecFormatVersion + 1;
  FixCrc(frame_);
  const Status s = Decode(frame_);
  EXPECT_EQ(s.code(), StatusCode::kUnimplemented);
  EXPECT_THAT(s.message(), HasSubstr("version"));
}

TEST_F(MapCodecCorruption, BadMagic) {
  frame_[0] = 'X';
  EXPECT_THAT(Decode(frame_).message(), HasSubstr("magic"));
}

TEST_F(MapCodecCorruption, EveryTruncationIsAnError) {
  for (size_t n = 0; n < frame_.size(); ++n) {
    const std::vector<uint8_t> cut(frame_.begin(), frame_.begin() + n);
    ASSERT_FALSE(DecodeFrame(cut).ok()) << "truncated at " << n;
  }
}

TEST_F(MapCodecCorruption, OversizedPayloadFieldIsCaught) {
  PutU32(frame_, 28, 1u << 30);
  FixCrc(frame_);
  EXPECT_THAT(Decode(frame_).message(), HasSubstr("payload size"));
}

TEST_F(MapCodecCorruption, TrailingBytesAreCaught) {
  frame_.insert(frame_.end() - 4, {1, 2, 3});
  FixCrc(frame_);
  EXPECT_EQ(Decode(frame_).code(), StatusCode::kDataLoss);
}

TEST_F(MapCodecCorruption, AbsurdWindowIsRefusedBeforeAllocation) {
  PutU32(frame_, 16, 200000);
  PutU32(frame_, 20, 200000);
  FixCrc(frame_);
  EXPECT_EQ(Decode(frame_).code(), StatusCode::kOutOfRange);
}

TEST_F(MapCodecCorruption, FrameLargerThanLimitIsRefused) {
  DecodeLimits limits;
  limits.max_frame_bytes = 64;
  EXPECT_EQ(Decode(frame_, limits).code(), StatusCode::kOutOfRange);
  limits = {};
  limits.max_cells = 100;
  EXPECT_EQ(Decode(frame_, limits).code(), StatusCode::kOutOfRange);
}

TEST_F(MapCodecCorruption, UnknownPackingAndCompression) {
  auto f = frame_;
  f[5] = 9;
  FixCrc(f);
  EXPECT_THAT(Decode(f).message(), HasSubstr("packing"));
  f = frame_;
  f[6] = 7;
  FixCrc(f);
  EXPECT_THAT(Decode(f).message(), HasSubstr("compression"));
}

// A decompression bomb: a tiny zstd payload that expands to 50 MB while the header
// promises a 64 x 64 window. The decoder must stop at the promised size.
TEST_F(MapCodecCorruption, DecompressionBombIsRefused) {
  const std::vector<uint8_t> zeros(50u << 20, 0);
  std::vector<uint8_t> bomb(ZSTD_compressBound(zeros.size()));
  bomb.resize(ZSTD_compress(bomb.data(), bomb.size(), zeros.data(), zeros.size(), 19));
  ASSERT_LT(bomb.size(), 4096u);
  std::vector<uint8_t> f(frame_.begin(), frame_.begin() + kCodecHeaderBytes);
  PutU32(f, 28, static_cast<uint32_t>(bomb.size()));
  f.insert(f.end(), bomb.begin(), bomb.end());
  ByteWriter(f).U32(Crc32(f.data(), f.size()));
  const Status s = Decode(f);
  EXPECT_EQ(s.code(), StatusCode::kDataLoss);
  EXPECT_THAT(s.message(), HasSubstr("zstd"));
}

TEST_F(MapCodecCorruption, InvalidTriStateCodeIsRejected) {
  CodecOptions raw;
  raw.compression = Compression::kNone;
  auto f = EncodeWindow(grid_, {0, 0, 8, 8}, raw);
  f[kCodecHeaderBytes] = 0xFF;  // four cells of code 3
  FixCrc(f);
  EXPECT_THAT(Decode(f).message(), HasSubstr("tri-state code"));
}

TEST_F(MapCodecCorruption, WindowOutsideTheGridLeavesItUntouched) {
  OccupancyGrid small(GridGeometry(0.05, 32, 32));
  auto decoded = DecodeFrame(frame_);
  ASSERT_TRUE(decoded.ok());
  EXPECT_EQ(ApplyFrame(*decoded, small).code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(small.CountState(CellState::kUnknown), 32 * 32);
}

}  // namespace
}  // namespace fleetmap::core
