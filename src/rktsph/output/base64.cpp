#include "rktsph/output/base64.hpp"

#include <sstream>

namespace rktsph {

namespace {
constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
}  // namespace

void Base64Encoder::put(std::uint8_t byte) {
  group_[group_size_++] = byte;
  if (group_size_ == 3) encode_group();
}

void Base64Encoder::put(std::span<const std::uint8_t> bytes) {
  for (const std::uint8_t byte : bytes)
    put(byte);
}

void Base64Encoder::put_little_endian(std::uint64_t value) {
  for (int byte_index = 0; byte_index < 8; ++byte_index) {
    put(static_cast<std::uint8_t>(value >> (8 * byte_index)));
  }
}

// Three input bytes are 24 bits, read as four 6-bit indices into the alphabet; a short group is
// zero-filled and the characters that carry no input bits are replaced by '='.
void Base64Encoder::encode_group() {
  if (character_count_ + 4 > characters_.size()) flush_characters();
  const std::uint32_t bits =
      (std::uint32_t{group_[0]} << 16) | (std::uint32_t{group_[1]} << 8) | std::uint32_t{group_[2]};
  const int significant_characters = group_size_ + 1;
  for (int index = 0; index < 4; ++index) {
    characters_[character_count_++] =
        index < significant_characters ? kAlphabet[(bits >> (18 - 6 * index)) & 0x3F] : '=';
  }
  group_ = {};
  group_size_ = 0;
}

void Base64Encoder::flush_characters() {
  out_.write(characters_.data(), static_cast<std::streamsize>(character_count_));
  character_count_ = 0;
}

void Base64Encoder::finish() {
  if (group_size_ > 0) encode_group();
  flush_characters();
}

std::string encode_base64(std::span<const std::uint8_t> bytes) {
  std::ostringstream out;
  Base64Encoder encoder(out);
  encoder.put(bytes);
  encoder.finish();
  return out.str();
}

}  // namespace rktsph
