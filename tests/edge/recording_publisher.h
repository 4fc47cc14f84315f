// A Publisher that keeps every message a node sends, for tests of either process to read back
// decoded (the sender's trailer split off as the receivers do).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "auth/trailer.h"
#include "edge/publisher.h"
#include "lcmtypes/convert.h"

namespace fleetmap::edge::testing {

struct SentMessage {
  Link link;
  std::string channel;
  std::vector<uint8_t> bytes;
};

// The message's LCM payload decoded as T (a failure fails the test and gives T()).
template <typename T>
T Payload(const SentMessage& m) {
  auto decoded = lcmtypes::Decode<T>(
      m.bytes.data(), static_cast<int>(auth::PayloadSize(m.bytes.data(), m.bytes.size())));
  EXPECT_TRUE(decoded.ok()) << m.channel << ": " << decoded.status().ToString();
  return decoded.ok() ? std::move(decoded).value() : T();
}

class RecordingPublisher : public Publisher {
 public:
  bool Publish(Link link, const std::string& channel, const std::vector<uint8_t>& bytes) override {
    sent.push_back({link, channel, bytes});
    return accept;
  }
  size_t RoomBytes(Link) const override { return room_bytes; }
  // Every message on `channel` from the `from`-th sent on, decoded.
  template <typename T>
  std::vector<T> Decoded(const std::string& channel, size_t from = 0) const {
    std::vector<T> out;
    for (size_t i = from; i < sent.size(); ++i)
      if (sent[i].channel == channel) out.push_back(Payload<T>(sent[i]));
    return out;
  }
  size_t Count(const std::string& channel, size_t from = 0) const {
    size_t n = 0;
    for (size_t i = from; i < sent.size(); ++i) n += sent[i].channel == channel;
    return n;
  }

  bool accept = true;  // what Publish answers: false as a full send buffer does
  // What RoomBytes answers: 0 as a link whose budget is spent, or that has messages waiting.
  size_t room_bytes = std::numeric_limits<size_t>::max();
  std::vector<SentMessage> sent;
};

}  // namespace fleetmap::edge::testing
