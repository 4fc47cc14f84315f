#include "core/map/map_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/image/map_render.h"
#include "core/io/file_io.h"
#include "tests/support/scratch_folder.h"

namespace fleetmap::core {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr char kMapYaml[] =
    "image: map.pgm\nresolution: 0.5\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
    "occupied_thresh: 0.65\nfree_thresh: 0.196\n";

class MapIoTest : public ::testing::Test {
 protected:
  std::string File(const std::string& name) const { return folder_.File(name); }
  void Write(const std::string& name, const std::string& text) const {
    std::ofstream(File(name), std::ios::binary) << text;
  }
  // A map.yaml (kMapYaml with `replace` substituted for `find`) and a P2 map.pgm.
  void WriteMap(const std::string& pgm, const std::string& find = "",
                const std::string& replace = "") {
    std::string yaml = kMapYaml;
    if (!find.empty()) yaml.replace(yaml.find(find), find.size(), replace);
    Write("map.yaml", yaml);
    Write("map.pgm", pgm);
  }
  Result<LoadedMap> Load() const { return LoadMapServerMap(File("map.yaml")); }
  std::vector<std::string> FileNames() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(folder_.path()))
      names.push_back(e.path().filename());
    std::sort(names.begin(), names.end());
    return names;
  }

  fleetmap::testing::ScratchFolder folder_;
};

std::string StatusText(const Result<LoadedMap>& r) { return r.ok() ? "ok" : r.status().ToString(); }

// A 7 x 5 grid with every state in every row and column, origin with yaw.
OccupancyGrid PatternGrid() {
  OccupancyGrid grid(GridGeometry(0.05, 7, 5, Pose2(1.5, -2.25, 0.3)));
  for (int y = 0; y < 5; ++y) {
    for (int x = 0; x < 7; ++x) grid.SetState({x, y}, static_cast<CellState>((x + 2 * y) % 3));
  }
  return grid;
}

void ExpectSameStates(const OccupancyGrid& a, const OccupancyGrid& b) {
  ASSERT_EQ(a.geometry(), b.geometry());
  for (int y = 0; y < a.geometry().height(); ++y) {
    for (int x = 0; x < a.geometry().width(); ++x) {
      EXPECT_EQ(a.state({x, y}), b.state({x, y})) << "cell " << x << ", " << y;
    }
  }
}

TEST_F(MapIoTest, TrinaryRoundTripKeepsGeometryAndEveryState) {
  const OccupancyGrid grid = PatternGrid();
  for (PgmFormat format : {PgmFormat::kBinary, PgmFormat::kAscii}) {
    MapSaveOptions options;
    options.pgm_format = format;
    ASSERT_TRUE(SaveMapServerMap(grid, File("saved.yaml"), options).ok());
    EXPECT_EQ(FileNames(), (std::vector<std::string>{"saved.pgm", "saved.yaml"}));
    const Result<LoadedMap> loaded = LoadMapServerMap(File("saved.yaml"));
    ASSERT_TRUE(loaded.ok()) << StatusText(loaded);
    ExpectSameStates(grid, loaded->grid);
    EXPECT_EQ(loaded->metadata.mode, MapMode::kTrinary);
    EXPECT_EQ(loaded->metadata.image_path, File("saved.pgm"));
  }
  const Result<std::string> yaml = ReadFileBytes(File("saved.yaml"), 4096);
  ASSERT_TRUE(yaml.ok());
  EXPECT_THAT(*yaml, HasSubstr("image: saved.pgm\n"));
  EXPECT_THAT(*yaml, HasSubstr("resolution: 0.05\n"));
  EXPECT_THAT(*yaml, HasSubstr("origin: [1.5, -2.25, 0.3]\n"));
  EXPECT_THAT(*yaml, HasSubstr("occupied_thresh: 0.65\nfree_thresh: 0.196\n"));
}

TEST_F(MapIoTest, TrinaryWritesMapSaverGreys) {
  OccupancyGrid grid(GridGeometry(0.1, 3, 1));
  grid.SetState({0, 0}, CellState::kOccupied);
  grid.SetState({1, 0}, CellState::kFree);
  ASSERT_TRUE(SaveMapServerMap(grid, File("m.yaml")).ok());
  const Result<GrayImage> image = ReadPgmFile(File("m.pgm"));
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->pixels, (std::vector<uint8_t>{0, 254, 205}));
}

TEST_F(MapIoTest, ScaleRoundTripKeepsStatesAndInBandProbabilities) {
  OccupancyGrid grid(GridGeometry(0.1, 9, 1, Pose2(0, 0, -1.0)));
  const std::vector<double> p = {0.197, 0.3, 0.5, 0.6, 0.6499, 0.1961, 0.8, 0.05};
  for (size_t i = 0; i < p.size(); ++i) grid.SetLogOdds({int(i), 0}, ProbabilityToLogOdds(p[i]));
  grid.SetState({8, 0}, CellState::kOccupied);
  MapSaveOptions options;
  options.mode = MapMode::kScale;
  ASSERT_TRUE(SaveMapServerMap(grid, File("s.yaml"), options).ok());
  const Result<LoadedMap> loaded = LoadMapServerMap(File("s.yaml"));
  ASSERT_TRUE(loaded.ok()) << StatusText(loaded);
  EXPECT_EQ(loaded->metadata.mode, MapMode::kScale);
  ExpectSameStates(grid, loaded->grid);
  for (int x = 0; x < 6; ++x) {  // between the thresholds: the probability itself
    EXPECT_NEAR(loaded->grid.probability({x, 0}), p[x], 1.0 / 255) << "cell " << x;
  }
  // Beyond the thresholds: certain, as map_server reports them 100 and 0.
  EXPECT_EQ(loaded->grid.log_odds({6, 0}), grid.CanonicalLogOdds(CellState::kOccupied));
  EXPECT_EQ(loaded->grid.log_odds({7, 0}), grid.CanonicalLogOdds(CellState::kFree));
  EXPECT_NEAR(loaded->grid.probability({8, 0}), grid.probability({8, 0}), 1.0 / 255);
}

TEST_F(MapIoTest, RawRoundTripWithinAPercent) {
  OccupancyGrid grid(GridGeometry(0.1, 4, 1));
  grid.SetLogOdds({0, 0}, ProbabilityToLogOdds(0.3));
  grid.SetState({1, 0}, CellState::kOccupied);
  grid.SetState({2, 0}, CellState::kFree);  // {3, 0} stays never observed
  MapSaveOptions options;
  options.mode = MapMode::kRaw;
  ASSERT_TRUE(SaveMapServerMap(grid, File("r.yaml"), options).ok());
  const Result<GrayImage> image = ReadPgmFile(File("r.pgm"));
  ASSERT_TRUE(image.ok());
  EXPECT_EQ(image->pixels, (std::vector<uint8_t>{30, 99, 1, 255}));
  const Result<LoadedMap> loaded = LoadMapServerMap(File("r.yaml"));
  ASSERT_TRUE(loaded.ok()) << StatusText(loaded);
  for (int x = 0; x < 4; ++x) {
    EXPECT_NEAR(loaded->grid.probability({x, 0}), grid.probability({x, 0}), 0.005) << x;
  }
  EXPECT_EQ(loaded->grid.log_odds({3, 0}), 0.0f);
}

TEST_F(MapIoTest, ImageTopRowIsTheGridTopRow) {
  WriteMap("P2 2 3 255\n0 0\n254 254\n205 205\n");
  const Result<LoadedMap> map = Load();
  ASSERT_TRUE(map.ok()) << StatusText(map);
  EXPECT_EQ(map->grid.state({1, 2}), CellState::kOccupied);
  EXPECT_EQ(map->grid.state({0, 1}), CellState::kFree);
  EXPECT_EQ(map->grid.state({0, 0}), CellState::kUnknown);
}

TEST_F(MapIoTest, OriginYawPlacesAKnownPixel) {
  // 6 x 4 image, one black pixel at image column 3, row 1: grid cell (3, 4 - 1 - 1) = (3, 2).
  WriteMap(
      "P2 6 4 255\n254 254 254 254 254 254\n254 254 254 0 254 254\n"
      "254 254 254 254 254 254\n254 254 254 254 254 254\n",
      "origin: [0.0, 0.0, 0.0]", "origin: [2.0, 1.0, 1.5707963267948966]");
  const Result<LoadedMap> map = Load();
  ASSERT_TRUE(map.ok()) << StatusText(map);
  EXPECT_EQ(map->grid.CountState(CellState::kOccupied), 1);
  EXPECT_EQ(map->grid.state({3, 2}), CellState::kOccupied);
  // Centre of cell (3, 2) in the grid frame is (1.75, 1.25) m; rotated by 90 degrees and
  // shifted by (2, 1) it is the world point (0.75, 2.75).
  const CellIndex cell = map->grid.geometry().WorldToCell({0.75, 2.75});
  EXPECT_EQ(cell, (CellIndex{3, 2}));
  EXPECT_EQ(map->grid.state(cell), CellState::kOccupied);
  EXPECT_DOUBLE_EQ(map->grid.geometry().origin().theta_rad, M_PI / 2);
}

TEST_F(MapIoTest, NegateSwapsBlackAndWhite) {
  WriteMap("P2 3 1 255\n0 255 100\n", "negate: 0", "negate: 1");
  const Result<LoadedMap> map = Load();
  ASSERT_TRUE(map.ok()) << StatusText(map);
  EXPECT_TRUE(map->metadata.negate);
  EXPECT_EQ(map->grid.state({0, 0}), CellState::kFree);
  EXPECT_EQ(map->grid.state({1, 0}), CellState::kOccupied);
  EXPECT_EQ(map->grid.state({2, 0}), CellState::kUnknown);  // p = 100/255 = 0.39
}

TEST_F(MapIoTest, TrinaryVersusScale) {
  // Grey 100: p = 155/255 = 0.608, between the thresholds.
  const std::string pgm = "P2 3 1 255\n0 100 254\n";
  WriteMap(pgm);
  const Result<LoadedMap> trinary = Load();
  ASSERT_TRUE(trinary.ok()) << StatusText(trinary);
  EXPECT_EQ(trinary->grid.log_odds({1, 0}), 0.0f);
  WriteMap(pgm, "negate: 0", "negate: 0\nmode: scale");
  const Result<LoadedMap> scale = Load();
  ASSERT_TRUE(scale.ok()) << StatusText(scale);
  EXPECT_NEAR(scale->grid.probability({1, 0}), 155.0 / 255, 1e-6);
  for (const Result<LoadedMap>* m : {&trinary, &scale}) {
    EXPECT_EQ((*m)->grid.log_odds({0, 0}), (*m)->grid.CanonicalLogOdds(CellState::kOccupied));
    EXPECT_EQ((*m)->grid.log_odds({2, 0}), (*m)->grid.CanonicalLogOdds(CellState::kFree));
  }
}

TEST_F(MapIoTest, RawModeReadsPercentages) {
  WriteMap("P2 5 1 255\n0 100 50 101 255\n", "negate: 0", "negate: 0\nmode: raw");
  const Result<LoadedMap> map = Load();
  ASSERT_TRUE(map.ok()) << StatusText(map);
  const OccupancyGrid& g = map->grid;
  EXPECT_EQ(g.log_odds({0, 0}), g.CanonicalLogOdds(CellState::kFree));
  EXPECT_EQ(g.log_odds({1, 0}), g.CanonicalLogOdds(CellState::kOccupied));
  EXPECT_EQ(g.log_odds({2, 0}), 0.0f);
  EXPECT_EQ(g.log_odds({3, 0}), 0.0f);
  EXPECT_EQ(g.log_odds({4, 0}), 0.0f);
  // With negate, 155 reads as 100 %, as ROS 1 map_server negates before raw.
  WriteMap("P2 1 1 255\n155\n", "negate: 0", "negate: 1\nmode: raw");
  const Result<LoadedMap> negated = Load();
  ASSERT_TRUE(negated.ok()) << StatusText(negated);
  EXPECT_EQ(negated->grid.state({0, 0}), CellState::kOccupied);
}

TEST_F(MapIoTest, PngMapsLoadThroughOpenCv) {
  const OccupancyGrid grid = PatternGrid();
  RenderOptions render;  // white, black and grey 205: map_saver's greys, in 3 channels
  ASSERT_TRUE(RenderGridToPng(grid, File("map.png"), render).ok());
  Write("map.yaml",
        "image: " + File("map.png") +  // absolute path
            "\nresolution: 0.05\norigin: [1.5, -2.25, 0.3]\nnegate: false\n"
            "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: trinary\n");
  const Result<LoadedMap> map = Load();
  ASSERT_TRUE(map.ok()) << StatusText(map);
  ExpectSameStates(grid, map->grid);
}

void ExpectYamlError(const Result<LoadedMap>& r, const std::vector<std::string>& substrings) {
  ASSERT_FALSE(r.ok());
  EXPECT_THAT(r.status().message(), HasSubstr("map.yaml: "));
  for (const std::string& s : substrings) EXPECT_THAT(r.status().message(), HasSubstr(s));
}

TEST_F(MapIoTest, YamlErrorsNameFileAndKey) {
  const std::string pgm = "P2 1 1 255\n0\n";
  WriteMap(pgm, "image: map.pgm\n", "");
  ExpectYamlError(Load(), {"missing key 'image'"});
  WriteMap(pgm, "resolution: 0.5", "resolution: -0.5");
  ExpectYamlError(Load(), {"key 'resolution' must be positive"});
  WriteMap(pgm, "resolution: 0.5", "resolution: fine");
  ExpectYamlError(Load(), {"key 'resolution' must be a number"});
  WriteMap(pgm, "resolution: 0.5", "resolution: .nan");
  ExpectYamlError(Load(), {"key 'resolution' must be finite"});
  WriteMap(pgm, "origin: [0.0, 0.0, 0.0]", "origin: [0.0, 0.0]");
  ExpectYamlError(Load(), {"key 'origin' must be a list of 3 numbers"});
  WriteMap(pgm, "origin: [0.0, 0.0, 0.0]", "origin: [0.0, x, 0.0]");
  ExpectYamlError(Load(), {"key 'origin' must be a number"});
  WriteMap(pgm, "negate: 0", "negate: 2");
  ExpectYamlError(Load(), {"key 'negate' must be 0 or 1"});
  WriteMap(pgm, "negate: 0\n", "");
  ExpectYamlError(Load(), {"missing key 'negate'"});
  WriteMap(pgm, "negate: 0", "negate: 0\nmode: fancy");
  ExpectYamlError(Load(), {"key 'mode' must be trinary, scale or raw, got 'fancy'"});
  WriteMap(pgm, "free_thresh: 0.196\n", "");
  ExpectYamlError(Load(), {"missing key 'free_thresh'"});
}

TEST_F(MapIoTest, SwappedThresholdsAreRefused) {
  WriteMap("P2 1 1 255\n0\n", "occupied_thresh: 0.65\nfree_thresh: 0.196",
           "occupied_thresh: 0.196\nfree_thresh: 0.65");
  ExpectYamlError(Load(), {"'free_thresh' (0.65", "'occupied_thresh' (0.196",
                           "0 < free_thresh < occupied_thresh < 1"});
}

TEST_F(MapIoTest, MalformedYamlIsAStatus) {
  Write("map.yaml", "image: [unclosed\n");
  ExpectYamlError(Load(), {"is not valid YAML"});
  Write("map.yaml", "- a list\n- not a mapping\n");
  ExpectYamlError(Load(), {"not a YAML mapping"});
  Write("map.yaml", "");
  ExpectYamlError(Load(), {"not a YAML mapping"});
  const Result<LoadedMap> no_yaml = LoadMapServerMap(File("absent.yaml"));
  ASSERT_FALSE(no_yaml.ok());
  EXPECT_EQ(no_yaml.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(no_yaml.status().message(), HasSubstr("absent.yaml"));
}

TEST_F(MapIoTest, MissingImageFileIsNotFound) {
  WriteMap("", "image: map.pgm", "image: elsewhere/gone.pgm");
  const Result<LoadedMap> r = Load();
  ExpectYamlError(r, {"key 'image'", "elsewhere/gone.pgm", "does not exist"});
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
}

TEST_F(MapIoTest, BadImagesAreStatusesNamingBothFiles) {
  WriteMap("P5 4 4 255\nxy");
  ExpectYamlError(Load(), {"map.pgm: PGM pixel data truncated"});
  WriteMap("P5\n200000 200000\n255\n");
  Result<LoadedMap> huge = Load();
  ExpectYamlError(huge, {"200000 x 200000 pixels exceeds the limit"});
  EXPECT_EQ(huge.status().code(), StatusCode::kOutOfRange);

  // A PNG header announcing 200000 x 200000 pixels, refused before OpenCV decodes it.
  const std::string png_header(
      "\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR\0\x03\x0d\x40\0\x03\x0d\x40"
      "\x08\x00\x00\x00\x00",
      29);
  Write("huge.png", png_header);
  WriteMap("", "image: map.pgm", "image: huge.png");
  huge = Load();
  ExpectYamlError(huge, {"huge.png: PNG image of 200000 x 200000 pixels exceeds the limit"});
  EXPECT_EQ(huge.status().code(), StatusCode::kOutOfRange);

  Write("junk.png", "this is not a picture");
  WriteMap("", "image: map.pgm", "image: junk.png");
  ExpectYamlError(Load(), {"junk.png: not an image OpenCV can decode"});
}

TEST_F(MapIoTest, SaveToUnwritablePlacesIsIoErrorAndLeavesNoFile) {
  const OccupancyGrid grid = PatternGrid();
  const Status no_folder = SaveMapServerMap(grid, File("no/such/folder/map.yaml"));
  EXPECT_EQ(no_folder.code(), StatusCode::kIoError);
  EXPECT_THAT(no_folder.message(), HasSubstr("no/such/folder/map.pgm"));

  Write("plain_file", "x");
  const Status under_file = SaveMapServerMap(grid, File("plain_file/map.yaml"));
  EXPECT_EQ(under_file.code(), StatusCode::kIoError);

  // The YAML cannot replace a folder: the image is written, the YAML and temp files are not.
  fs::create_directory(File("map.yaml"));
  const Status onto_folder = SaveMapServerMap(grid, File("map.yaml"));
  EXPECT_EQ(onto_folder.code(), StatusCode::kIoError);
  EXPECT_THAT(onto_folder.message(), HasSubstr("map.yaml"));
  EXPECT_EQ(FileNames(), (std::vector<std::string>{"map.pgm", "map.yaml", "plain_file"}));
  EXPECT_TRUE(fs::is_directory(File("map.yaml")));

  if (geteuid() != 0) {  // root writes into read-only folders anyway
    fs::create_directory(File("ro"));
    fs::permissions(File("ro"), fs::perms::owner_read | fs::perms::owner_exec);
    const Status read_only = SaveMapServerMap(grid, File("ro/map.yaml"));
    EXPECT_EQ(read_only.code(), StatusCode::kIoError);
    EXPECT_THAT(read_only.message(), HasSubstr("Permission denied"));
    EXPECT_TRUE(fs::is_empty(File("ro")));
  }
}

TEST_F(MapIoTest, SaveOptionsAreValidated) {
  MapSaveOptions options;
  options.mode = MapMode::kScale;
  options.thresholds.free_probability = 0.5;
  options.thresholds.occupied_probability = 0.5 + 1.0 / 255;
  const Status narrow = SaveMapServerMap(PatternGrid(), File("m.yaml"), options);
  EXPECT_EQ(narrow.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(narrow.message(), HasSubstr("scale mode needs"));
  options.thresholds.free_probability = 0.7;
  EXPECT_THAT(SaveMapServerMap(PatternGrid(), File("m.yaml"), options).message(),
              HasSubstr("MapSaveOptions.thresholds"));
  EXPECT_EQ(SaveMapServerMap(PatternGrid(), File("m.pgm")).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(FileNames().empty());
}

}  // namespace
}  // namespace fleetmap::core
