// The map codec (core/codec/map_codec.h): any bytes as a codec frame, as they come out of a tile
// message. A frame that decodes must write into a grid that holds its window, be refused by one
// that does not (leaving it untouched), and survive a re-encoding with its own packing and
// compression: encode(decode(x)) decodes to the same values.
#include "core/codec/map_codec.h"
#include "fuzz/checksum_repair.h"
#include "fuzz/fuzz_check.h"

namespace fleetmap::fuzz {
namespace {

// Windows whose grid would exceed this are only decoded, not applied (keeps executions fast).
constexpr int64_t kMaxAppliedCells = 1 << 20;

core::OccupancyGrid GridFor(const core::CellWindow& w, int shrink) {
  return core::OccupancyGrid(
      core::GridGeometry(0.05, w.x0 + w.width - shrink, w.y0 + w.height, core::Pose2()));
}

void CheckRoundTrip(const core::DecodedFrame& frame, const core::OccupancyGrid& grid) {
  core::CodecOptions options;
  options.packing = frame.packing;
  options.compression = frame.compression;
  options.level = 1;
  auto again = core::DecodeFrame(core::EncodeWindow(grid, frame.window, options));
  FUZZ_REQUIRE(again.ok() && again->window == frame.window && again->packing == frame.packing);
  // Log-odds quanta beyond the grid's clamping limits come back clamped, once.
  core::OccupancyGrid grid2 = GridFor(frame.window, 0);
  FUZZ_REQUIRE(core::ApplyFrame(*again, grid2).ok());
  auto third = core::DecodeFrame(core::EncodeWindow(grid2, frame.window, options));
  FUZZ_REQUIRE(third.ok() && third->values == again->values);
  if (frame.packing != core::CellPacking::kLogOddsInt8) FUZZ_REQUIRE(again->values == frame.values);
}

void Check(const core::DecodedFrame& frame) {
  const core::CellWindow& w = frame.window;
  FUZZ_REQUIRE(w.width > 0 && w.height > 0 && w.x0 >= 0 && w.y0 >= 0);
  FUZZ_REQUIRE(static_cast<int64_t>(frame.values.size()) == w.num_cells());
  if ((int64_t{w.x0} + w.width) * (int64_t{w.y0} + w.height) > kMaxAppliedCells) return;
  core::OccupancyGrid grid = GridFor(w, 0);
  FUZZ_REQUIRE(core::ApplyFrame(frame, grid).ok());
  if (w.x0 + w.width > 1) {
    core::OccupancyGrid small = GridFor(w, 1);
    FUZZ_REQUIRE(!core::ApplyFrame(frame, small).ok());
    FUZZ_REQUIRE(small.cells() == GridFor(w, 1).cells());
  }
  CheckRoundTrip(frame, grid);
}

}  // namespace
}  // namespace fleetmap::fuzz

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  auto frame = core::DecodeFrame(data, size);
  if (frame.ok()) fuzz::Check(*frame);
  std::vector<uint8_t> repaired(data, data + size);
  if (size >= core::kCodecHeaderBytes + core::kCodecTrailerBytes &&
      fuzz::RepairTrailingCrc32(repaired)) {
    frame = core::DecodeFrame(repaired);
    if (frame.ok()) fuzz::Check(*frame);
  }
  return 0;
}
