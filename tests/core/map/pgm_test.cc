#include "core/map/pgm.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "core/io/file_io.h"
#include "tests/support/scratch_folder.h"

namespace fleetmap::core {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

// Each test's files in a scratch folder of its own.
class PgmTest : public ::testing::Test {
 protected:
  std::string File(const std::string& name) const { return folder_.File(name); }

  fleetmap::testing::ScratchFolder folder_;
};

GrayImage Gradient(int width, int height) {
  GrayImage image{width, height, std::vector<uint8_t>(static_cast<size_t>(width) * height)};
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = static_cast<uint8_t>(i * 7);
  return image;
}

std::string Decoded(const Result<GrayImage>& r) { return r.ok() ? "ok" : r.status().ToString(); }

void ExpectError(std::string_view bytes, StatusCode code, const std::string& substring,
                 const PgmReadOptions& options = {}) {
  const Result<GrayImage> r = DecodePgm(bytes, options);
  ASSERT_FALSE(r.ok()) << "accepted: " << bytes.substr(0, 40);
  EXPECT_EQ(r.status().code(), code) << r.status().ToString();
  EXPECT_THAT(r.status().message(), HasSubstr(substring));
}

TEST_F(PgmTest, BinaryRoundTrip) {
  const GrayImage image = Gradient(37, 5);  // includes values 0..255, also whitespace bytes
  const std::string bytes = EncodePgm(image, PgmFormat::kBinary);
  EXPECT_EQ(bytes.substr(0, 3), "P5\n");
  const Result<GrayImage> back = DecodePgm(bytes);
  ASSERT_TRUE(back.ok()) << Decoded(back);
  EXPECT_EQ(back->width, 37);
  EXPECT_EQ(back->height, 5);
  EXPECT_EQ(back->pixels, image.pixels);
}

TEST_F(PgmTest, AsciiRoundTripKeepsLinesShort) {
  const GrayImage image = Gradient(40, 3);
  const std::string bytes = EncodePgm(image, PgmFormat::kAscii);
  EXPECT_EQ(bytes.substr(0, 3), "P2\n");
  size_t line_start = 0;
  for (size_t nl = bytes.find('\n'); nl != std::string::npos; nl = bytes.find('\n', line_start)) {
    EXPECT_LE(nl - line_start, 70u);
    line_start = nl + 1;
  }
  const Result<GrayImage> back = DecodePgm(bytes);
  ASSERT_TRUE(back.ok()) << Decoded(back);
  EXPECT_EQ(back->pixels, image.pixels);
}

TEST_F(PgmTest, FileRoundTripBothFormats) {
  const GrayImage image = Gradient(9, 4);
  for (PgmFormat format : {PgmFormat::kBinary, PgmFormat::kAscii}) {
    ASSERT_TRUE(WritePgmFile(image, File("a.pgm"), format).ok());
    const Result<GrayImage> back = ReadPgmFile(File("a.pgm"));
    ASSERT_TRUE(back.ok()) << Decoded(back);
    EXPECT_EQ(back->pixels, image.pixels);
  }
}

TEST_F(PgmTest, CommentsAndAnyWhitespaceInHeader) {
  const Result<GrayImage> ascii =
      DecodePgm("P2# magic\n# a comment line\n3\t# width\r\n2 #h\n\n255\n1 2 3\n# mid\n4 5 6\n");
  ASSERT_TRUE(ascii.ok()) << Decoded(ascii);
  EXPECT_EQ(ascii->width, 3);
  EXPECT_EQ(ascii->height, 2);
  EXPECT_EQ(ascii->pixels, (std::vector<uint8_t>{1, 2, 3, 4, 5, 6}));

  // A comment right after maxval ends the header; the raster starts with a space byte.
  const std::string binary = std::string("P5 # x\n2\n# y\n2 255# end\n") + "  \n\x07";
  const Result<GrayImage> p5 = DecodePgm(binary);
  ASSERT_TRUE(p5.ok()) << Decoded(p5);
  EXPECT_EQ(p5->pixels, (std::vector<uint8_t>{' ', ' ', '\n', 7}));
}

TEST_F(PgmTest, SmallMaxvalIsRescaledTo255) {
  const Result<GrayImage> r = DecodePgm("P2 4 1 100 0 50 99 100");
  ASSERT_TRUE(r.ok()) << Decoded(r);
  EXPECT_EQ(r->pixels, (std::vector<uint8_t>{0, 128, 252, 255}));
  const Result<GrayImage> bits = DecodePgm(std::string("P5 2 1 1\n\x01\x00", 11));
  ASSERT_TRUE(bits.ok()) << Decoded(bits);
  EXPECT_EQ(bits->pixels, (std::vector<uint8_t>{255, 0}));
}

TEST_F(PgmTest, WrongMagicIsNamed) {
  ExpectError("", StatusCode::kInvalidArgument, "P5 or P2");
  ExpectError("GIF89a", StatusCode::kInvalidArgument, "P5 or P2");
  ExpectError("P6 1 1 255\n...", StatusCode::kInvalidArgument, "colour PPM");
  ExpectError("P4 1 1\n.", StatusCode::kInvalidArgument, "found P4");
  ExpectError("P55 1 1 255\n.", StatusCode::kInvalidArgument, "magic number is followed by");
}

TEST_F(PgmTest, MissingOrGarbageHeaderFieldsAreNamed) {
  ExpectError("P5\n", StatusCode::kDataLoss, "ends before the width");
  ExpectError("P5 4 # only a width\n", StatusCode::kDataLoss, "ends before the height");
  ExpectError("P2 2 2", StatusCode::kDataLoss, "ends before the maxval");
  ExpectError("P5 abc 2 255\n", StatusCode::kInvalidArgument, "width is not a number");
  ExpectError("P5 2 -2 255\n", StatusCode::kInvalidArgument, "height is not a number");
  ExpectError("P5 12x 2 255\n", StatusCode::kInvalidArgument, "width is followed by 'x'");
  ExpectError("P5 2 2 25.5\n", StatusCode::kInvalidArgument, "maxval is followed by '.'");
  ExpectError("P5 99999999999 2 255\n", StatusCode::kOutOfRange, "width is absurdly large");
  ExpectError("P5 0 2 255\n", StatusCode::kInvalidArgument, "size must be positive");
  ExpectError("P5 1 1 255", StatusCode::kDataLoss, "no pixel data");
}

TEST_F(PgmTest, MaxvalOutsideEightBitsIsRefused) {
  ExpectError("P5 1 1 0\n.", StatusCode::kInvalidArgument, "maxval must be 1..255, got 0");
  ExpectError("P5 1 1 65535\n..", StatusCode::kUnimplemented, "16-bit PGM");
  ExpectError("P5 1 1 256\n..", StatusCode::kUnimplemented, "16-bit PGM");
  ExpectError("P5 1 1 70000\n..", StatusCode::kInvalidArgument, "maxval must be 1..255");
}

TEST_F(PgmTest, TruncatedPixelDataIsDataLoss) {
  ExpectError("P5 3 2 255\nabcde", StatusCode::kDataLoss, "expected 6 bytes, found 5");
  ExpectError("P2 3 2 255\n1 2 3 4 5", StatusCode::kDataLoss, "cannot hold 6 values");
  ExpectError("P2 3 2 255\n1 2 3 4 5 # where is the sixth\n", StatusCode::kDataLoss,
              "expected 6 values, found 5");
}

TEST_F(PgmTest, BadPixelValuesAreNamed) {
  ExpectError("P2 2 2 255\n1 2 x 4", StatusCode::kInvalidArgument,
              "pixel (x 0, row 1) is not a number");
  ExpectError("P2 2 1 200\n1 201", StatusCode::kInvalidArgument,
              "pixel (x 1, row 0) value 201 exceeds maxval 200");
  ExpectError("P5 2 1 100\n\x05\xc8", StatusCode::kInvalidArgument, "value 200 exceeds maxval 100");
}

TEST_F(PgmTest, AbsurdSizeIsRefusedBeforeAllocating) {
  // 4e10 pixels: allocating would throw or exhaust memory, so a status proves the order.
  ExpectError("P5\n200000 200000\n255\n", StatusCode::kOutOfRange,
              "200000 x 200000 pixels exceeds the limit");
  ExpectError("P2 200000 200000 255\n0", StatusCode::kOutOfRange, "exceeds the limit");
  // Exactly at the limit but with 3 bytes of pixels: refused as truncated, not allocated.
  ExpectError("P5 10000 10000 255\nabc", StatusCode::kDataLoss, "expected 100000000 bytes");
}

TEST_F(PgmTest, TrailingDataIsIgnoredByDefaultAndRefusedWhenStrict) {
  PgmReadOptions strict;
  strict.allow_trailing_data = false;
  const std::string p5 = "P5 2 1 255\nab\nP5 1 1 255\nc";
  const Result<GrayImage> lenient = DecodePgm(p5);
  ASSERT_TRUE(lenient.ok()) << Decoded(lenient);
  EXPECT_EQ(lenient->pixels, (std::vector<uint8_t>{'a', 'b'}));
  ExpectError(p5, StatusCode::kDataLoss, "13 bytes of trailing data", strict);

  ExpectError("P2 2 1 255\n1 2 3\n", StatusCode::kDataLoss, "trailing data", strict);
  EXPECT_TRUE(DecodePgm("P2 2 1 255\n1 2 3\n").ok());
  // Whitespace and comments after the last P2 value are not data.
  EXPECT_TRUE(DecodePgm("P2 2 1 255\n1 2\n# end\n\n", strict).ok());
}

TEST_F(PgmTest, FileErrorsNameThePath) {
  const Result<GrayImage> missing = ReadPgmFile(File("none.pgm"));
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.status().code(), StatusCode::kNotFound);
  EXPECT_THAT(missing.status().message(), HasSubstr("none.pgm"));

  std::ofstream(File("bad.pgm")) << "P5 4 4 255\nxy";
  const Result<GrayImage> bad = ReadPgmFile(File("bad.pgm"));
  ASSERT_FALSE(bad.ok());
  EXPECT_THAT(bad.status().message(), HasSubstr("bad.pgm: PGM pixel data truncated"));
}

TEST_F(PgmTest, AtomicWriteReplacesContent) {
  ASSERT_TRUE(WriteFileAtomically(File("f"), "first version").ok());
  ASSERT_TRUE(WriteFileAtomically(File("f"), "second").ok());
  const Result<std::string> bytes = ReadFileBytes(File("f"), 100);
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(*bytes, "second");
  EXPECT_EQ(ReadFileBytes(File("f"), 3).status().code(), StatusCode::kOutOfRange);
  // Without fsync (kept across a process crash only) it replaces the content the same way.
  ASSERT_TRUE(WriteFileAtomically(File("f"), "third", Durability::kProcessCrash).ok());
  EXPECT_EQ(ReadFileBytes(File("f"), 100).value(), "third");
  EXPECT_EQ(WriteFileAtomically(File("missing/f"), "x", Durability::kProcessCrash).code(),
            StatusCode::kIoError);
}

TEST_F(PgmTest, FailedAtomicWriteLeavesNoFile) {
  const Status no_folder = WriteFileAtomically(File("missing/f.pgm"), "x");
  EXPECT_EQ(no_folder.code(), StatusCode::kIoError);
  EXPECT_THAT(no_folder.message(), HasSubstr("missing/f.pgm"));
  EXPECT_THAT(no_folder.message(), HasSubstr("temporary file"));

  // Renaming onto a folder fails after the temporary file was written: it must be removed.
  fs::create_directory(File("taken"));
  const Status onto_folder = WriteFileAtomically(File("taken"), "x");
  EXPECT_EQ(onto_folder.code(), StatusCode::kIoError);
  EXPECT_THAT(onto_folder.message(), HasSubstr("rename"));
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder_.path()))
    names.push_back(entry.path().filename());
  EXPECT_EQ(names, std::vector<std::string>{"taken"});
}

}  // namespace
}  // namespace fleetmap::core
