#include <gtest/gtest.h>

#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "rktsph/output/base64.hpp"

namespace rktsph::base64_test {
namespace {

std::string encode_text(const std::string& text) {
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  return encode_base64(bytes);
}

// The test vectors of RFC 4648, section 10.
TEST(Base64, Rfc4648TestVectors) {
  EXPECT_EQ(encode_text(""), "");
  EXPECT_EQ(encode_text("f"), "Zg==");
  EXPECT_EQ(encode_text("fo"), "Zm8=");
  EXPECT_EQ(encode_text("foo"), "Zm9v");
  EXPECT_EQ(encode_text("foob"), "Zm9vYg==");
  EXPECT_EQ(encode_text("fooba"), "Zm9vYmE=");
  EXPECT_EQ(encode_text("foobar"), "Zm9vYmFy");
}

// 0xFB 0xEF 0xBE splits into four 6-bit groups of 62 ('+'), 0xFF 0xFF 0xFF into four of 63 ('/'):
// the two characters outside the letters and digits.
TEST(Base64, LastAlphabetCharacters) {
  EXPECT_EQ(encode_base64(std::vector<std::uint8_t>{0xFB, 0xEF, 0xBE}), "++++");
  EXPECT_EQ(encode_base64(std::vector<std::uint8_t>{0xFF, 0xFF, 0xFF}), "////");
  EXPECT_EQ(encode_base64(std::vector<std::uint8_t>{0x00, 0x00, 0x00}), "AAAA");
}

TEST(Base64, LittleEndianWordsAndLongInputCrossTheInternalBuffer) {
  std::ostringstream out;
  Base64Encoder encoder(out);
  encoder.put_little_endian(0x0807060504030201ULL);
  encoder.finish();
  // The bytes 01 02 .. 08 in that order.
  EXPECT_EQ(out.str(), encode_base64(std::vector<std::uint8_t>{1, 2, 3, 4, 5, 6, 7, 8}));

  // 3 * 5000 bytes of "foo" must give 5000 copies of "Zm9v": longer than the 4 KiB block the
  // encoder collects characters in.
  std::ostringstream long_out;
  Base64Encoder long_encoder(long_out);
  for (int repeat = 0; repeat < 5000; ++repeat) {
    long_encoder.put('f');
    long_encoder.put('o');
    long_encoder.put('o');
  }
  long_encoder.finish();
  std::string expected;
  for (int repeat = 0; repeat < 5000; ++repeat)
    expected += "Zm9v";
  EXPECT_EQ(long_out.str(), expected);
}

}  // namespace
}  // namespace rktsph::base64_test
