#include "core/map/pgm.h"

#include <cstdlib>
#include <cstring>

#include "core/io/file_io.h"
#include "core/map/grid_geometry.h"

namespace fleetmap::core {
namespace {

// Numbers in a header larger than this are refused before any arithmetic on them.
constexpr int64_t kMaxHeaderNumber = 1'000'000'000;

bool IsPgmSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}
bool IsDigit(char c) { return c >= '0' && c <= '9'; }

std::string Printable(char c) {
  if (c >= 0x21 && c < 0x7f) return std::string("'") + c + "'";
  return "byte " + std::to_string(static_cast<unsigned char>(c));
}

// Reads the tokens of a PGM header (and of a P2 raster): unsigned decimals separated by
// whitespace and '#' comments running to the end of the line.
class PgmScanner {
 public:
  explicit PgmScanner(std::string_view bytes) : bytes_(bytes) {}

  size_t pos() const { return pos_; }
  void set_pos(size_t pos) { pos_ = pos; }
  bool AtEnd() const { return pos_ >= bytes_.size(); }
  char Peek() const { return bytes_[pos_]; }
  std::string_view Rest() const { return bytes_.substr(pos_); }

  void SkipComment() {
    while (!AtEnd() && Peek() != '\n' && Peek() != '\r') ++pos_;
    if (!AtEnd()) ++pos_;
  }
  void SkipSpaceAndComments() {
    while (!AtEnd()) {
      if (Peek() == '#') {
        SkipComment();
      } else if (IsPgmSpace(Peek())) {
        ++pos_;
      } else {
        return;
      }
    }
  }

  // Skips separators, then reads one number that must end at a separator or the end.
  Result<int64_t> ReadNumber(const std::string& what) {
    return ReadNumberNamed([&what] { return what; });
  }

  // `what()` names the number in an error, and is called only for one: a P2 raster's pixel
  // names would otherwise be built for every value read.
  template <typename NameFn>
  Result<int64_t> ReadNumberNamed(const NameFn& what) {
    SkipSpaceAndComments();
    if (AtEnd()) return DataLoss("PGM ends before the " + what());
    if (!IsDigit(Peek())) {
      return InvalidArgument("PGM " + what() + " is not a number: found " + Printable(Peek()));
    }
    int64_t value = 0;
    while (!AtEnd() && IsDigit(Peek())) {
      value = value * 10 + (Peek() - '0');
      if (value > kMaxHeaderNumber) return OutOfRange("PGM " + what() + " is absurdly large");
      ++pos_;
    }
    if (!AtEnd() && !IsPgmSpace(Peek()) && Peek() != '#') {
      return InvalidArgument("PGM " + what() + " is followed by " + Printable(Peek()));
    }
    return value;
  }

 private:
  std::string_view bytes_;
  size_t pos_ = 0;
};

struct PgmHeader {
  PgmFormat format = PgmFormat::kBinary;
  int width = 0;
  int height = 0;
  int maxval = 255;
};

Result<PgmFormat> ReadMagic(PgmScanner& scanner, std::string_view bytes) {
  if (bytes.size() < 2 || bytes[0] != 'P') {
    return InvalidArgument("not a PGM file: it must start with P5 or P2");
  }
  const char kind = bytes[1];
  if (kind == '3' || kind == '6')
    return InvalidArgument("P" + std::string(1, kind) + " is a colour PPM image, not a PGM");
  if (kind != '5' && kind != '2') {
    return InvalidArgument("not a PGM file: magic number must be P5 or P2, found P" +
                           std::string(1, kind));
  }
  scanner.set_pos(2);
  if (!scanner.AtEnd() && !IsPgmSpace(scanner.Peek()) && scanner.Peek() != '#') {
    return InvalidArgument("PGM magic number is followed by " + Printable(scanner.Peek()));
  }
  return kind == '5' ? PgmFormat::kBinary : PgmFormat::kAscii;
}

Status CheckHeaderValues(const PgmHeader& h) {
  if (h.width <= 0 || h.height <= 0) {
    return InvalidArgument("PGM size must be positive, got " + std::to_string(h.width) + " x " +
                           std::to_string(h.height));
  }
  if (int64_t{h.width} * h.height > kMaxGridCells) {
    return OutOfRange("PGM image of " + std::to_string(h.width) + " x " + std::to_string(h.height) +
                      " pixels exceeds the limit of " + std::to_string(kMaxGridCells) + " pixels");
  }
  if (h.maxval == 0) return InvalidArgument("PGM maxval must be 1..255, got 0");
  if (h.maxval > 255 && h.maxval <= 65535) {
    return Unimplemented("16-bit PGM (maxval " + std::to_string(h.maxval) +
                         ") is not supported, only maxval 1..255");
  }
  if (h.maxval > 255) {
    return InvalidArgument("PGM maxval must be 1..255, got " + std::to_string(h.maxval));
  }
  return OkStatus();
}

Result<PgmHeader> ReadHeader(PgmScanner& scanner, std::string_view bytes) {
  PgmHeader h;
  Result<PgmFormat> format = ReadMagic(scanner, bytes);
  if (!format.ok()) return format.status();
  h.format = *format;
  Result<int64_t> width = scanner.ReadNumber("width");
  if (!width.ok()) return width.status();
  Result<int64_t> height = scanner.ReadNumber("height");
  if (!height.ok()) return height.status();
  Result<int64_t> maxval = scanner.ReadNumber("maxval");
  if (!maxval.ok()) return maxval.status();
  h.width = static_cast<int>(*width);
  h.height = static_cast<int>(*height);
  h.maxval = static_cast<int>(*maxval);
  FLEETMAP_RETURN_IF_ERROR(CheckHeaderValues(h));
  // Exactly one whitespace byte (or a comment up to its newline) separates maxval from a P5
  // raster, whose first byte may itself look like whitespace.
  if (scanner.AtEnd()) return DataLoss("PGM ends after the header: no pixel data");
  if (scanner.Peek() == '#') {
    scanner.SkipComment();
  } else {
    scanner.set_pos(scanner.pos() + 1);
  }
  return h;
}

// Refuses a raster that cannot fit in the remaining bytes before its buffer is allocated: a
// P5 pixel takes one byte, a P2 value at least one digit and one separator.
Status CheckRasterFits(const PgmHeader& h, size_t remaining_bytes) {
  const int64_t n = int64_t{h.width} * h.height;
  if (h.format == PgmFormat::kBinary && static_cast<int64_t>(remaining_bytes) < n) {
    return DataLoss("PGM pixel data truncated: expected " + std::to_string(n) + " bytes, found " +
                    std::to_string(remaining_bytes));
  }
  if (h.format == PgmFormat::kAscii && static_cast<int64_t>(remaining_bytes) < 2 * n - 1) {
    return DataLoss("PGM pixel data truncated: " + std::to_string(remaining_bytes) +
                    " bytes cannot hold " + std::to_string(n) + " values");
  }
  return OkStatus();
}

uint8_t Rescale(int64_t value, int maxval) {
  if (maxval == 255) return static_cast<uint8_t>(value);
  return static_cast<uint8_t>((value * 255 + maxval / 2) / maxval);
}

std::string PixelName(int64_t i, int width) {
  return "pixel (x " + std::to_string(i % width) + ", row " + std::to_string(i / width) + ")";
}

Status ReadBinaryRaster(PgmScanner& scanner, const PgmHeader& h, GrayImage& image,
                        const PgmReadOptions& options) {
  const std::string_view rest = scanner.Rest();  // long enough: checked by CheckRasterFits
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    const int v = static_cast<unsigned char>(rest[i]);
    if (v > h.maxval) {
      return InvalidArgument("PGM " + PixelName(static_cast<int64_t>(i), h.width) + " value " +
                             std::to_string(v) + " exceeds maxval " + std::to_string(h.maxval));
    }
    image.pixels[i] = Rescale(v, h.maxval);
  }
  const size_t trailing = rest.size() - image.pixels.size();
  if (trailing > 0 && !options.allow_trailing_data) {
    return DataLoss(std::to_string(trailing) + " bytes of trailing data after the PGM pixels");
  }
  return OkStatus();
}

Status ReadAsciiRaster(PgmScanner& scanner, const PgmHeader& h, GrayImage& image,
                       const PgmReadOptions& options) {
  const int64_t n = static_cast<int64_t>(image.pixels.size());
  for (int64_t i = 0; i < n; ++i) {
    scanner.SkipSpaceAndComments();
    if (scanner.AtEnd()) {
      return DataLoss("PGM pixel data truncated: expected " + std::to_string(n) +
                      " values, found " + std::to_string(i));
    }
    Result<int64_t> v = scanner.ReadNumberNamed([&] { return PixelName(i, h.width); });
    if (!v.ok()) return v.status();
    if (*v > h.maxval) {
      return InvalidArgument("PGM " + PixelName(i, h.width) + " value " + std::to_string(*v) +
                             " exceeds maxval " + std::to_string(h.maxval));
    }
    image.pixels[static_cast<size_t>(i)] = Rescale(*v, h.maxval);
  }
  scanner.SkipSpaceAndComments();
  if (!scanner.AtEnd() && !options.allow_trailing_data) {
    return DataLoss("trailing data after the last PGM pixel value: " + Printable(scanner.Peek()));
  }
  return OkStatus();
}

void AppendAsciiRaster(const GrayImage& image, std::string& out) {
  constexpr int kValuesPerLine = 17;  // "255 " x 17 = 68 characters
  for (int row = 0; row < image.height; ++row) {
    for (int x = 0; x < image.width; ++x) {
      out += std::to_string(image.at(x, row));
      const bool line_end = x + 1 == image.width || (x + 1) % kValuesPerLine == 0;
      out += line_end ? '\n' : ' ';
    }
  }
}

}  // namespace

Result<GrayImage> DecodePgm(std::string_view bytes, const PgmReadOptions& options) {
  PgmScanner scanner(bytes);
  Result<PgmHeader> header = ReadHeader(scanner, bytes);
  if (!header.ok()) return header.status();
  FLEETMAP_RETURN_IF_ERROR(CheckRasterFits(*header, scanner.Rest().size()));
  GrayImage image;
  image.width = header->width;
  image.height = header->height;
  image.pixels.resize(static_cast<size_t>(int64_t{image.width} * image.height));
  FLEETMAP_RETURN_IF_ERROR(header->format == PgmFormat::kBinary
                               ? ReadBinaryRaster(scanner, *header, image, options)
                               : ReadAsciiRaster(scanner, *header, image, options));
  return image;
}

std::string EncodePgm(const GrayImage& image, PgmFormat format) {
  assert(image.width > 0 && image.height > 0);
  assert(image.pixels.size() == static_cast<size_t>(int64_t{image.width} * image.height));
  std::string out = format == PgmFormat::kBinary ? "P5\n" : "P2\n";
  out += std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
  if (format == PgmFormat::kBinary) {
    out.append(reinterpret_cast<const char*>(image.pixels.data()), image.pixels.size());
  } else {
    AppendAsciiRaster(image, out);
  }
  return out;
}

Result<GrayImage> ReadPgmFile(const std::string& path, const PgmReadOptions& options) {
  Result<std::string> bytes = ReadFileBytes(path, kMaxPgmFileBytes);
  if (!bytes.ok()) return bytes.status();
  Result<GrayImage> image = DecodePgm(*bytes, options);
  if (!image.ok()) return image.status().WithContext(path);
  return image;
}

Status WritePgmFile(const GrayImage& image, const std::string& path, PgmFormat format) {
  return WriteFileAtomically(path, EncodePgm(image, format));
}

}  // namespace fleetmap::core
