#pragma once
// 64-bit FNV-1a. The typed adders write values in a fixed byte order (little-endian), so that
// hashes and fingerprints are the same on every machine; bytes() takes memory as it lies, for keys
// that never leave the process.
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace cdb {

class Fnv1a {
 public:
  void byte(std::uint8_t b) {
    state_ ^= b;
    state_ *= 0x100000001b3ULL;
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) byte(std::uint8_t(v >> (8 * i)));
  }
  void bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) byte(p[i]);
  }
  void i64(std::int64_t v) { u64(std::uint64_t(v)); }
  void f64(double v) { u64(std::bit_cast<std::uint64_t>(v)); }  // the IEEE-754 bits
  void text(std::string_view s) {
    u64(s.size());  // length first, so ("ab","c") and ("a","bc") differ
    for (char c : s) byte(std::uint8_t(c));
  }
  [[nodiscard]] std::uint64_t value() const { return state_; }

 private:
  std::uint64_t state_ = 0xcbf29ce484222325ULL;
};

}  // namespace cdb
