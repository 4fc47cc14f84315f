// A small pcapng reader (section header, interface description and enhanced packet blocks,
// either byte order, any timestamp resolution) and the reassembly of the TCP byte streams it
// holds (Ethernet, optional VLAN tag, IPv4). Segments are ordered by sequence number per
// direction; retransmitted bytes are dropped and gaps are left for the telegram splitter to
// resynchronise over.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/result.h"

namespace fleetmap::sim::sick {

struct TcpSegment {
  double time_s = 0.0;  // capture time, seconds since the epoch
  std::string bytes;
};

struct TcpStream {
  uint32_t src_ip = 0, dst_ip = 0;
  uint16_t src_port = 0, dst_port = 0;
  std::vector<TcpSegment> segments;  // in sequence order, without overlaps
  uint64_t gaps = 0;                 // places where bytes were missing from the capture
};

// Parses a whole pcapng file held in memory (InvalidArgument or DataLoss on a malformed one).
core::Result<std::vector<TcpStream>> ReassemblePcapng(const std::string& file);

}  // namespace fleetmap::sim::sick
