// Cuts a TCP byte stream into CoLa telegram payloads: reassembles telegrams split across
// segments, skips garbage between telegrams, drops telegrams with a bad CoLa-B checksum or an
// impossible length (a length field of 4 GB is garbage, not an allocation) and resynchronises
// on the next telegram start. The buffer never holds more than one maximal telegram plus the
// bytes of one Feed call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "core/result.h"
#include "drivers/sick/cola_frame.h"

namespace fleetmap::drivers::sick {

struct TelegramSplitterOptions {
  ColaProtocol protocol = ColaProtocol::kColaB;
  // Longest accepted payload, bytes. A 1141-point LMS511 scan with RSSI is about 3.5 KB in
  // CoLa-B and 10 KB in CoLa-A; 1 MiB leaves room for multi-echo scans. Range: >= 16.
  size_t max_payload_bytes = 1 << 20;
  core::Status Validate() const;
};

struct TelegramSplitterStats {
  uint64_t telegrams = 0;      // complete payloads returned
  uint64_t garbage_bytes = 0;  // bytes skipped while looking for a telegram start
  uint64_t bad_checksums = 0;  // CoLa-B telegrams whose XOR did not match
  uint64_t oversized = 0;      // length fields (or unterminated CoLa-A telegrams) over the limit
};

class TelegramSplitter {
 public:
  explicit TelegramSplitter(TelegramSplitterOptions options = {});

  // Appends received bytes.
  void Feed(const uint8_t* data, size_t size);
  void Feed(const std::string& bytes) {
    Feed(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
  }
  // The next complete payload (without framing), or nothing until more bytes arrive.
  std::optional<std::string> Next();
  // Forgets buffered bytes (after a reconnect); statistics stay.
  void Reset();

  size_t buffered_bytes() const { return buffer_.size() - start_; }
  const TelegramSplitterStats& stats() const { return stats_; }
  const TelegramSplitterOptions& options() const { return options_; }

 private:
  std::optional<std::string> NextColaA();
  std::optional<std::string> NextColaB();
  // Skips `n` bytes as garbage.
  void Skip(size_t n);
  void Compact();
  const uint8_t* data() const { return reinterpret_cast<const uint8_t*>(buffer_.data()) + start_; }

  const TelegramSplitterOptions options_;
  std::string buffer_;
  size_t start_ = 0;  // first unread byte of buffer_
  // CoLa-A: the unfinished telegram at start_ holds neither ETX nor STX before this offset
  // (so that each Feed scans only the new bytes, not the whole telegram again).
  size_t scanned_ = 0;
  TelegramSplitterStats stats_;
};

}  // namespace fleetmap::drivers::sick
