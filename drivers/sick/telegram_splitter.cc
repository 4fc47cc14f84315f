#include "drivers/sick/telegram_splitter.h"

#include <algorithm>
#include <cstring>

namespace fleetmap::drivers::sick {
namespace {

// Every payload starts with a command type such as "sSN": a cheap check that a candidate
// telegram start is real and not four 0x02 bytes inside binary scan data.
bool LooksLikeCommandStart(const uint8_t* p, size_t available) {
  if (available < 1) return true;  // cannot tell yet
  if (p[0] != 's') return false;
  if (available < 3) return true;
  return std::isupper(p[1]) && std::isupper(p[2]);
}

}  // namespace

core::Status TelegramSplitterOptions::Validate() const {
  if (max_payload_bytes < 16) {
    return core::InvalidArgument("telegram_splitter.max_payload_bytes must be >= 16");
  }
  return core::OkStatus();
}

TelegramSplitter::TelegramSplitter(TelegramSplitterOptions options) : options_(options) {
  assert(options_.Validate().ok());
}

void TelegramSplitter::Feed(const uint8_t* data, size_t size) {
  Compact();
  buffer_.append(reinterpret_cast<const char*>(data), size);
}

void TelegramSplitter::Reset() {
  buffer_.clear();
  start_ = 0;
  scanned_ = 0;
}

void TelegramSplitter::Skip(size_t n) {
  stats_.garbage_bytes += n;
  start_ += n;
  scanned_ = 0;
}

void TelegramSplitter::Compact() {
  if (start_ == 0) return;
  buffer_.erase(0, start_);
  start_ = 0;
}

std::optional<std::string> TelegramSplitter::Next() {
  std::optional<std::string> payload =
      options_.protocol == ColaProtocol::kColaA ? NextColaA() : NextColaB();
  if (payload) ++stats_.telegrams;
  return payload;
}

std::optional<std::string> TelegramSplitter::NextColaA() {
  while (buffered_bytes() > 0) {
    const uint8_t* p = data();
    const size_t n = buffered_bytes();
    const auto* stx = static_cast<const uint8_t*>(std::memchr(p, kStx, n));
    if (stx == nullptr) {
      Skip(n);
      return std::nullopt;
    }
    if (stx != p) Skip(static_cast<size_t>(stx - p));
    p = data();
    const size_t available = buffered_bytes();
    if (!LooksLikeCommandStart(p + 1, available - 1)) {
      Skip(1);
      continue;
    }
    // The telegram ends at ETX; a second STX before it means the first one was cut off.
    size_t end = std::max<size_t>(1, scanned_);
    while (end < available && p[end] != kEtx && p[end] != kStx) ++end;
    scanned_ = end;
    if (end == available) {
      if (available > options_.max_payload_bytes + 2) {
        ++stats_.oversized;
        Skip(1);
        continue;
      }
      return std::nullopt;
    }
    if (p[end] == kStx) {
      Skip(end);
      continue;
    }
    std::string payload(reinterpret_cast<const char*>(p + 1), end - 1);
    start_ += end + 1;
    scanned_ = 0;
    return payload;
  }
  return std::nullopt;
}

std::optional<std::string> TelegramSplitter::NextColaB() {
  static const uint8_t kSync[4] = {kStx, kStx, kStx, kStx};
  while (buffered_bytes() > 0) {
    const uint8_t* p = data();
    const size_t n = buffered_bytes();
    const auto* sync = std::search(p, p + n, kSync, kSync + 4);
    if (sync == p + n) {
      // Keep a possible partial sync at the end (up to 3 bytes of 0x02).
      size_t keep = 0;
      while (keep < 3 && keep < n && p[n - 1 - keep] == kStx) ++keep;
      Skip(n - keep);
      return std::nullopt;
    }
    if (sync != p) Skip(static_cast<size_t>(sync - p));
    p = data();
    const size_t available = buffered_bytes();
    if (available < kColaBHeaderBytes) return std::nullopt;
    const uint32_t length =
        (uint32_t{p[4]} << 24) | (uint32_t{p[5]} << 16) | (uint32_t{p[6]} << 8) | uint32_t{p[7]};
    if (length < 4 || length > options_.max_payload_bytes) {
      ++stats_.oversized;
      Skip(1);
      continue;
    }
    if (!LooksLikeCommandStart(p + 8, available - 8)) {
      Skip(1);
      continue;
    }
    if (available < kColaBHeaderBytes + length + 1) return std::nullopt;
    const uint8_t* body = p + kColaBHeaderBytes;
    if (ColaBChecksum(body, length) != body[length]) {
      ++stats_.bad_checksums;
      Skip(1);
      continue;
    }
    std::string payload(reinterpret_cast<const char*>(body), length);
    start_ += kColaBHeaderBytes + length + 1;
    return payload;
  }
  return std::nullopt;
}

}  // namespace fleetmap::drivers::sick
