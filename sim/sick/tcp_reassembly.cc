#include "sim/sick/tcp_reassembly.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

namespace fleetmap::sim::sick {
namespace {

struct RawSegment {
  uint32_t seq = 0;
  double time_s = 0.0;
  size_t order = 0;
  std::string bytes;
};

using FlowKey = std::tuple<uint32_t, uint16_t, uint32_t, uint16_t>;

class PcapngParser {
 public:
  explicit PcapngParser(const std::string& file) : f_(file) {}
  core::Status Run(std::map<FlowKey, std::vector<RawSegment>>& flows);

 private:
  uint32_t U32(size_t at) const {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) {
      const uint32_t b = static_cast<uint8_t>(f_[at + i]);
      v |= little_ ? b << (8 * i) : b << (8 * (3 - i));
    }
    return v;
  }
  uint16_t U16(size_t at) const {
    const uint16_t a = static_cast<uint8_t>(f_[at]), b = static_cast<uint8_t>(f_[at + 1]);
    return little_ ? static_cast<uint16_t>(a | (b << 8)) : static_cast<uint16_t>((a << 8) | b);
  }
  void InterfaceBlock(size_t body, size_t body_len);
  void PacketBlock(size_t body, size_t body_len, std::map<FlowKey, std::vector<RawSegment>>& flows);

  const std::string& f_;
  bool little_ = true;
  std::vector<double> resolution_s_;  // per interface
  size_t order_ = 0;
};

uint16_t NetU16(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }
uint32_t NetU32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

// Ethernet -> IPv4 -> TCP; false for anything else.
bool DecodeTcp(const uint8_t* p, size_t n, FlowKey& key, RawSegment& seg) {
  if (n < 14) return false;
  size_t off = 12;
  uint16_t ethertype = NetU16(p + off);
  if (ethertype == 0x8100 && n >= 18) off += 4, ethertype = NetU16(p + off);
  off += 2;
  if (ethertype != 0x0800 || n < off + 20) return false;
  const uint8_t* ip = p + off;
  const size_t ihl = (ip[0] & 0x0F) * 4u;
  const size_t ip_len = std::min<size_t>(NetU16(ip + 2), n - off);
  if ((ip[0] >> 4) != 4 || ip[9] != 6 || ihl < 20 || ip_len < ihl + 20) return false;
  const uint8_t* tcp = ip + ihl;
  const size_t tcp_header = (tcp[12] >> 4) * 4u;
  if (tcp_header < 20 || ihl + tcp_header > ip_len) return false;
  key = {NetU32(ip + 12), NetU16(tcp), NetU32(ip + 16), NetU16(tcp + 2)};
  seg.seq = NetU32(tcp + 4);
  seg.bytes.assign(reinterpret_cast<const char*>(tcp + tcp_header), ip_len - ihl - tcp_header);
  return true;
}

void PcapngParser::InterfaceBlock(size_t body, size_t body_len) {
  double resolution = 1e-6;
  for (size_t o = body + 8; o + 4 <= body + body_len;) {
    const uint16_t code = U16(o), len = U16(o + 2);
    if (code == 0) break;
    if (code == 9 && len == 1 && o + 5 <= f_.size()) {
      const uint8_t v = static_cast<uint8_t>(f_[o + 4]);
      resolution = (v & 0x80) ? std::pow(2.0, -(v & 0x7F)) : std::pow(10.0, -v);
    }
    o += 4 + ((len + 3u) & ~3u);
  }
  resolution_s_.push_back(resolution);
}

void PcapngParser::PacketBlock(size_t body, size_t body_len,
                               std::map<FlowKey, std::vector<RawSegment>>& flows) {
  if (body_len < 20) return;
  const uint32_t interface = U32(body);
  const uint64_t ts = (uint64_t{U32(body + 4)} << 32) | U32(body + 8);
  const uint32_t captured = U32(body + 12);
  if (captured > body_len - 20) return;
  FlowKey key;
  RawSegment seg;
  const auto* packet = reinterpret_cast<const uint8_t*>(f_.data() + body + 20);
  if (!DecodeTcp(packet, captured, key, seg) || seg.bytes.empty()) return;
  const double res = interface < resolution_s_.size() ? resolution_s_[interface] : 1e-6;
  seg.time_s = static_cast<double>(ts) * res;
  seg.order = order_++;
  flows[key].push_back(std::move(seg));
}

core::Status PcapngParser::Run(std::map<FlowKey, std::vector<RawSegment>>& flows) {
  size_t pos = 0;
  while (pos + 12 <= f_.size()) {
    const uint32_t type_le = static_cast<uint8_t>(f_[pos]) | static_cast<uint8_t>(f_[pos + 1]) << 8;
    if (type_le == 0x0D0A && f_.size() >= pos + 12) {  // section header: learn the byte order
      const uint32_t magic = static_cast<uint8_t>(f_[pos + 8]);
      little_ = magic == 0x4D;
    }
    const uint32_t type = U32(pos), length = U32(pos + 4);
    if (length < 12 || length % 4 != 0 || pos + length > f_.size()) {
      return core::DataLoss("pcapng block at byte " + std::to_string(pos) + " has a bad length");
    }
    const size_t body = pos + 8, body_len = length - 12;
    if (type == 1) InterfaceBlock(body, body_len);
    if (type == 6) PacketBlock(body, body_len, flows);
    pos += length;
  }
  if (pos != f_.size()) return core::DataLoss("pcapng file ends inside a block");
  return core::OkStatus();
}

TcpStream Reassemble(const FlowKey& key, std::vector<RawSegment> raw) {
  TcpStream s;
  std::tie(s.src_ip, s.src_port, s.dst_ip, s.dst_port) = key;
  const uint32_t base = raw.front().seq;
  std::stable_sort(raw.begin(), raw.end(), [base](const RawSegment& a, const RawSegment& b) {
    return a.seq - base < b.seq - base;
  });
  uint64_t expected = 0;  // relative to base
  for (RawSegment& r : raw) {
    const uint64_t begin = r.seq - base, end = begin + r.bytes.size();
    if (end <= expected) continue;  // retransmission
    if (begin > expected) ++s.gaps;
    const size_t skip = begin < expected ? static_cast<size_t>(expected - begin) : 0;
    s.segments.push_back({r.time_s, r.bytes.substr(skip)});
    expected = end;
  }
  return s;
}

}  // namespace

core::Result<std::vector<TcpStream>> ReassemblePcapng(const std::string& file) {
  if (file.size() < 12 || file.compare(0, 4, "\x0A\x0D\x0D\x0A") != 0) {
    return core::InvalidArgument("not a pcapng file (no section header block)");
  }
  std::map<FlowKey, std::vector<RawSegment>> flows;
  PcapngParser parser(file);
  FLEETMAP_RETURN_IF_ERROR(parser.Run(flows));
  std::vector<TcpStream> streams;
  for (auto& [key, raw] : flows) streams.push_back(Reassemble(key, std::move(raw)));
  return streams;
}

}  // namespace fleetmap::sim::sick
