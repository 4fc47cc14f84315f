// The map codec on the LivingLab grid (60 m x 18 m at 5 cm = 1200 x 360 cells): keyframe and
// one-pallet delta sizes against a ROS OccupancyGrid (1 byte per cell), encode and decode
// times, and the packing/compression alternatives that chose the defaults.
#include <benchmark/benchmark.h>

#include <string>

#include "bench/figure_reporter.h"
#include "core/codec/tile_delta.h"
#include "sim/livinglab_map.h"

namespace fleetmap::bench {
namespace {

using core::CellPacking;
using core::Compression;

const core::OccupancyGrid& Hall() {
  static const core::OccupancyGrid hall = sim::MakeLivingLabMap();
  return hall;
}

// The hall after one 1.2 m x 0.8 m pallet was placed in an aisle.
const core::OccupancyGrid& HallWithPallet() {
  static const core::OccupancyGrid hall = [] {
    core::OccupancyGrid g = Hall();
    sim::AddPalletToMap(g, 20.0, 4.0);
    return g;
  }();
  return hall;
}

void BM_EncodeKeyframe(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(core::EncodeAllTiles(Hall()));
}
BENCHMARK(BM_EncodeKeyframe)->Unit(benchmark::kMicrosecond);

void BM_DecodeKeyframe(benchmark::State& state) {
  const auto tiles = core::EncodeAllTiles(Hall());
  core::OccupancyGrid receiver(Hall().geometry());
  for (auto _ : state) {
    const core::Status s = core::ApplyTiles(tiles, 64, receiver);
    if (!s.ok()) state.SkipWithError(s.ToString().c_str());
  }
}
BENCHMARK(BM_DecodeKeyframe)->Unit(benchmark::kMicrosecond);

void BM_EncodePalletDelta(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(core::EncodeChangedTiles(Hall(), HallWithPallet()));
}
BENCHMARK(BM_EncodePalletDelta)->Unit(benchmark::kMicrosecond);

void BM_DecodePalletDelta(benchmark::State& state) {
  const auto tiles = core::EncodeChangedTiles(Hall(), HallWithPallet());
  core::OccupancyGrid receiver = Hall();
  for (auto _ : state) {
    const core::Status s = core::ApplyTiles(tiles, 64, receiver);
    if (!s.ok()) state.SkipWithError(s.ToString().c_str());
  }
}
BENCHMARK(BM_DecodePalletDelta)->Unit(benchmark::kMicrosecond);

// Keyframe bytes (as 64 x 64 tiles) for every packing and compression we considered.
void RecordAlternatives() {
  struct Alternative {
    CellPacking packing;
    Compression compression;
    int level;
  };
  const Alternative alternatives[] = {
      {CellPacking::kTriState8Bit, Compression::kNone, 0},
      {CellPacking::kTriState8Bit, Compression::kZlib, 6},
      {CellPacking::kTriState8Bit, Compression::kZstd, 3},
      {CellPacking::kTriState2Bit, Compression::kNone, 0},
      {CellPacking::kTriState2Bit, Compression::kZlib, 6},
      {CellPacking::kTriState2Bit, Compression::kZstd, 1},
      {CellPacking::kTriState2Bit, Compression::kZstd, 3},
      {CellPacking::kTriState2Bit, Compression::kZstd, 19},
      {CellPacking::kLogOddsInt8, Compression::kZstd, 3},
  };
  for (const Alternative& a : alternatives) {
    core::TileOptions options;
    options.codec.packing = a.packing;
    options.codec.compression = a.compression;
    options.codec.level = a.level;
    const std::string name = std::string("codec.alt.") + core::CellPackingName(a.packing) + "_" +
                             core::CompressionName(a.compression) +
                             (a.level ? std::to_string(a.level) : "");
    RecordFigure(name + ".keyframe_bytes",
                 double(core::TotalFrameBytes(core::EncodeAllTiles(Hall(), options))), "B");
    RecordFigure(
        name + ".pallet_delta_bytes",
        double(core::TotalFrameBytes(core::EncodeChangedTiles(Hall(), HallWithPallet(), options))),
        "B");
  }
  core::CodecOptions whole;
  RecordFigure("codec.alt.single_frame_keyframe_bytes",
               double(core::EncodeWindow(Hall(), Hall().geometry().full_window(), whole).size()),
               "B");
}

}  // namespace
}  // namespace fleetmap::bench

int main(int argc, char** argv) {
  using namespace fleetmap::bench;
  const auto& hall = Hall();
  int changed = 0;
  for (int64_t i = 0; i < hall.geometry().num_cells(); ++i) {
    changed += fleetmap::core::TriStateClassifier()(hall.cells()[i]) !=
               fleetmap::core::TriStateClassifier()(HallWithPallet().cells()[i]);
  }
  RecordFigure("codec.raw_bytes", double(hall.geometry().num_cells()), "B");
  RecordFigure("codec.keyframe_bytes",
               double(fleetmap::core::TotalFrameBytes(fleetmap::core::EncodeAllTiles(hall))), "B");
  RecordFigure("codec.keyframe_tiles", double(fleetmap::core::EncodeAllTiles(hall).size()),
               "tiles");
  const auto delta = fleetmap::core::EncodeChangedTiles(hall, HallWithPallet());
  RecordFigure("codec.pallet_delta_bytes", double(fleetmap::core::TotalFrameBytes(delta)), "B");
  RecordFigure("codec.pallet_delta_tiles", double(delta.size()), "tiles");
  RecordFigure("codec.pallet_changed_cells", changed, "cells");
  RecordAlternatives();
  TimeFigure("BM_EncodeKeyframe", "codec.encode_us", "us");
  TimeFigure("BM_DecodeKeyframe", "codec.decode_us", "us");
  TimeFigure("BM_EncodePalletDelta", "codec.delta_encode_us", "us");
  TimeFigure("BM_DecodePalletDelta", "codec.delta_decode_us", "us");
  return RunBenchmarksAndPrintFigures(argc, argv);
}
