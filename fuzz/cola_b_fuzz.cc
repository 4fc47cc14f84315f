// CoLa-B over TCP (the scanners' binary protocol): stream framing (02 02 02 02, length, XOR
// checksum), command replies and binary LMDscandata, through the scanner client's receive path
// (cola_stream.h); then once more with every frame's checksum repaired, so that mutations of
// scan data reach the LMDscandata parser.
#include "fuzz/checksum_repair.h"
#include "fuzz/cola_stream.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  if (size < 1) return 0;
  std::string stream(reinterpret_cast<const char*>(data) + 1, size - 1);
  const size_t piece_bytes = 1 + data[0] * data[0];
  fuzz::ColaStreamTarget target(drivers::sick::ColaProtocol::kColaB);
  target.Run(stream, piece_bytes);
  if (fuzz::RepairColaBChecksums(stream)) target.Run(stream, piece_bytes);
  return 0;
}
