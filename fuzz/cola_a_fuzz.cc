// CoLa-A over TCP (port 2111 or 2112 set to ASCII): stream framing (STX ... ETX), command
// replies and LMDscandata in hex ASCII, through the scanner client's receive path
// (cola_stream.h).
#include "fuzz/cola_stream.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fleetmap;
  if (size < 1) return 0;
  const std::string stream(reinterpret_cast<const char*>(data) + 1, size - 1);
  fuzz::ColaStreamTarget(drivers::sick::ColaProtocol::kColaA).Run(stream, 1 + data[0] * data[0]);
  return 0;
}
