// Base64 (RFC 4648, standard alphabet, '=' padding) for the inline binary arrays of VTK XML files.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <span>
#include <string>

namespace rktsph {

/// Encodes bytes as they arrive and writes the characters to a stream, so that a large array is
/// never held twice in memory. Bytes are buffered in groups of three; finish() writes the last
/// partial group with padding. The encoder writes nothing on its own destruction: a caller that
/// forgets finish() gets a visibly truncated array rather than a silently "complete" one.
class Base64Encoder {
 public:
  explicit Base64Encoder(std::ostream& out) : out_(out) {}
  Base64Encoder(const Base64Encoder&) = delete;
  Base64Encoder& operator=(const Base64Encoder&) = delete;

  void put(std::uint8_t byte);
  void put(std::span<const std::uint8_t> bytes);
  /// Appends the 8 bytes of `value` in little-endian order, whatever the host order.
  void put_little_endian(std::uint64_t value);
  /// Writes the pending partial group (with '=' padding) and any buffered characters.
  void finish();

 private:
  void encode_group();
  void flush_characters();

  std::ostream& out_;
  std::array<std::uint8_t, 3> group_{};
  int group_size_ = 0;
  // Characters are collected and written in blocks because one ostream::write per 4 characters
  // would dominate the cost of writing a large VTU file.
  std::array<char, 4096> characters_{};
  std::size_t character_count_ = 0;
};

/// Convenience for small inputs and tests.
std::string encode_base64(std::span<const std::uint8_t> bytes);

}  // namespace rktsph
