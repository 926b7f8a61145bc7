#include <gtest/gtest.h>

#include <unistd.h>

#include <bit>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>

#include "rktsph/output/json_writer.hpp"

namespace rktsph::json_writer_test {
namespace {

std::uint64_t bits(double value) {
  return std::bit_cast<std::uint64_t>(value);
}

TEST(JsonValue, EscapesQuotesBackslashAndControlCharacters) {
  EXPECT_EQ(json_quote("plain"), "\"plain\"");
  EXPECT_EQ(json_quote("say \"hi\""), R"("say \"hi\"")");
  EXPECT_EQ(json_quote("C:\\dir\\file"), R"("C:\\dir\\file")");
  EXPECT_EQ(json_quote("a\nb\tc\rd\be\ff"), R"("a\nb\tc\rd\be\ff")");
  EXPECT_EQ(json_quote(std::string("nul\0x", 5)), R"("nul\u0000x")");
  EXPECT_EQ(json_quote("\x01\x1f"), R"("\u0001\u001f")");
  // 0x20 and above (space, DEL, UTF-8 bytes) need no escape.
  EXPECT_EQ(json_quote(" \x7f\xc3\xa9"), "\" \x7f\xc3\xa9\"");
}

TEST(JsonValue, IntegralDoublesStayRecognisablyReal) {
  EXPECT_EQ(json_number(2.0), "2.0");
  EXPECT_EQ(json_number(-0.0), "-0.0");
  EXPECT_EQ(json_number(0.0), "0.0");
  EXPECT_EQ(json_number(1.5), "1.5");
  EXPECT_EQ(json_number(1e300), "1e+300");
  EXPECT_EQ(JsonValue(2).compact(), "2");
}

TEST(JsonValue, NonFiniteNumbersBecomeNull) {
  EXPECT_EQ(json_number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(json_number(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(json_number(-std::numeric_limits<double>::infinity()), "null");
  JsonValue array = JsonValue::array();
  array.push_back(std::nan("")).push_back(1.5);
  EXPECT_EQ(array.compact(), "[null,1.5]");
}

// Round trip: the printed number, read back with strtod, must be the same double bit for bit.
void expect_round_trip(double value) {
  const std::string text = json_number(value);
  char* end = nullptr;
  const double parsed = std::strtod(text.c_str(), &end);
  EXPECT_EQ(*end, '\0') << text;
  EXPECT_EQ(bits(parsed), bits(value)) << text;
  // JSON numbers: no leading '+', no "inf"/"nan", no leading '.'.
  EXPECT_TRUE(text[0] == '-' || (text[0] >= '0' && text[0] <= '9')) << text;
  EXPECT_EQ(text.find_first_not_of("0123456789+-.eE"), std::string::npos) << text;
}

TEST(JsonValue, DoublesRoundTrip) {
  for (const double value : {0.0, -0.0, 0.1, 1.0 / 3.0, -3.5e-7, 12345.678, 1e21, 1e-7, DBL_MAX,
                             -DBL_MAX, DBL_MIN, 4.9e-324, DBL_EPSILON, 9007199254740993.0}) {
    expect_round_trip(value);
  }
  // Random bit patterns cover exponents and mantissas no hand-picked list would.
  std::mt19937_64 generator(20240501);
  int checked = 0;
  while (checked < 20000) {
    const double value = std::bit_cast<double>(generator());
    if (!std::isfinite(value)) continue;
    expect_round_trip(value);
    ++checked;
  }
}

TEST(JsonValue, CompactAndPrettyLayout) {
  JsonValue summary = JsonValue::object();
  summary.set("case", "bar \"impact\"")
      .set("steps", 1200)
      .set("converged", true)
      .set("error", nullptr)
      .set("ratio", 0.5)
      .set("empty", JsonValue::array())
      .set("times", JsonValue::array().push_back(0.0).push_back(2.5e-3))
      .set("counts", JsonValue::object().set("nodes", std::size_t{51}).set("offset", -3));
  EXPECT_EQ(summary.compact(),
            R"({"case":"bar \"impact\"","steps":1200,"converged":true,"error":null,)"
            R"("ratio":0.5,"empty":[],"times":[0.0,0.0025],"counts":{"nodes":51,"offset":-3}})");
  EXPECT_EQ(summary.pretty(),
            "{\n"
            "  \"case\": \"bar \\\"impact\\\"\",\n"
            "  \"steps\": 1200,\n"
            "  \"converged\": true,\n"
            "  \"error\": null,\n"
            "  \"ratio\": 0.5,\n"
            "  \"empty\": [],\n"
            "  \"times\": [\n"
            "    0.0,\n"
            "    0.0025\n"
            "  ],\n"
            "  \"counts\": {\n"
            "    \"nodes\": 51,\n"
            "    \"offset\": -3\n"
            "  }\n"
            "}");
}

TEST(JsonValue, SetReplacesAnExistingKeyInPlace) {
  JsonValue object = JsonValue::object();
  object.set("a", 1).set("b", 2).set("a", "one");
  EXPECT_EQ(object.compact(), R"({"a":"one","b":2})");
}

TEST(JsonValue, IntegersKeepFullRange) {
  JsonValue array = JsonValue::array();
  array.push_back(std::numeric_limits<std::int64_t>::min())
      .push_back(std::numeric_limits<std::uint64_t>::max())
      .push_back(false);
  EXPECT_EQ(array.compact(), "[-9223372036854775808,18446744073709551615,false]");
}

TEST(JsonValue, WrongKindOfContainerThrows) {
  JsonValue array = JsonValue::array();
  JsonValue number = 1.0;
  EXPECT_THROW(array.set("key", 1), std::logic_error);
  EXPECT_THROW(number.push_back(1), std::logic_error);
}

// An outside check that the output is JSON at all: Python's json module must accept it.
TEST(JsonValue, PythonJsonModuleAcceptsTheOutput) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "/usr/bin/python3 missing";
  JsonValue document = JsonValue::object();
  document.set("text", std::string("q\" b\\ n\n c\x01 \xc3\xa9"))
      .set("numbers", JsonValue::array().push_back(-0.0).push_back(DBL_MIN).push_back(1e300))
      .set("nan", std::nan(""))
      .set("nested", JsonValue::object().set("list", JsonValue::array()));
  const std::filesystem::path directory = std::filesystem::temp_directory_path();
  const std::string stem = "rktsph_json_test_" + std::to_string(::getpid());
  const std::filesystem::path file = directory / (stem + ".json");
  const std::filesystem::path script = directory / (stem + ".py");
  {
    // Re-checks decoded values, not just that parsing succeeded.
    std::ofstream stream(script);
    stream << R"PY(import json, sys
d = json.load(open(sys.argv[1], encoding="utf-8"))
ok = (d["text"] == 'q" b\\ n\n c\x01 \u00e9' and d["nan"] is None
      and str(d["numbers"][0]) == "-0.0" and d["numbers"][2] == 1e300
      and d["nested"] == {"list": []})
sys.exit(0 if ok else 1)
)PY";
  }
  for (const std::string& text : {document.compact(), document.pretty()}) {
    {
      std::ofstream stream(file);
      stream << text;
    }
    const std::string command =
        "/usr/bin/python3 '" + script.string() + "' '" + file.string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0) << text;
  }
  std::filesystem::remove(script);
  std::filesystem::remove(file);
}

}  // namespace
}  // namespace rktsph::json_writer_test
