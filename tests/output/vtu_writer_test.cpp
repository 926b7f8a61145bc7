// The .vtu and .pvd files are checked by an independent Python reader (read_vtu.py, which decodes
// the VTK XML format with the standard library only), so a writer bug cannot be hidden by a
// matching bug in a C++ reader. Every value must come back bit for bit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <array>
#include <bit>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "rktsph/core/point_cloud.hpp"
#include "rktsph/output/pvd_writer.hpp"
#include "rktsph/output/vtu_writer.hpp"

namespace rktsph::vtu_writer_test {
namespace {

namespace fs = std::filesystem;

const char* const kPython = "/usr/bin/python3";
// Taken lexically (parent_path, not "..") so it works even before tests/data exists.
const fs::path kReader = fs::path(RKTSPH_TEST_DATA_DIR).parent_path() / "output" / "read_vtu.py";

// --- A minimal JSON reader for the script's output (numbers through strtod, which is exact). ---
// A member struct declared ahead and operator[] defined after both types are complete: clang 14
// with libstdc++ 12 cannot instantiate std::pair<std::string, Json> inside Json.
struct JsonMember;
struct Json {
  using Array = std::vector<Json>;
  using Object = std::vector<JsonMember>;
  std::variant<std::nullptr_t, bool, double, std::string, Array, Object> value;

  const Json& operator[](const std::string& key) const;
  const Array& array() const { return std::get<Array>(value); }
  double number() const { return std::get<double>(value); }
  const std::string& text() const { return std::get<std::string>(value); }
};
struct JsonMember {
  std::string name;
  Json value;
};

const Json& Json::operator[](const std::string& key) const {
  for (const auto& [name, member] : std::get<Object>(value)) {
    if (name == key) return member;
  }
  throw std::out_of_range("no key " + key);
}

class JsonParser {
 public:
  explicit JsonParser(std::string text) : text_(std::move(text)) {}

  Json parse() {
    Json result = parse_value();
    skip_space();
    if (position_ != text_.size()) throw std::runtime_error("trailing characters");
    return result;
  }

 private:
  void skip_space() {
    while (position_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[position_])))
      ++position_;
  }
  bool consume(char expected) {
    skip_space();
    if (position_ < text_.size() && text_[position_] == expected) {
      ++position_;
      return true;
    }
    return false;
  }
  void expect(char expected) {
    if (!consume(expected)) throw std::runtime_error(std::string("expected ") + expected);
  }
  bool consume_word(const std::string& word) {
    skip_space();
    if (text_.compare(position_, word.size(), word) != 0) return false;
    position_ += word.size();
    return true;
  }
  std::string parse_string() {
    expect('"');
    std::string result;
    while (position_ < text_.size() && text_[position_] != '"') {
      char character = text_[position_++];
      if (character == '\\') {
        const char escaped = text_.at(position_++);
        if (escaped == 'u') {
          result += static_cast<char>(std::stoi(text_.substr(position_, 4), nullptr, 16));
          position_ += 4;
          continue;
        }
        character = escaped == 'n' ? '\n' : escaped == 't' ? '\t' : escaped;
      }
      result += character;
    }
    expect('"');
    return result;
  }
  Json parse_value() {
    skip_space();
    if (position_ >= text_.size()) throw std::runtime_error("unexpected end");
    const char first = text_[position_];
    if (first == '{') {
      ++position_;
      Json::Object members;
      if (!consume('}')) {
        do {
          std::string key = parse_string();
          expect(':');
          members.push_back({std::move(key), parse_value()});
        } while (consume(','));
        expect('}');
      }
      return Json{std::move(members)};
    }
    if (first == '[') {
      ++position_;
      Json::Array elements;
      if (!consume(']')) {
        do {
          elements.push_back(parse_value());
        } while (consume(','));
        expect(']');
      }
      return Json{std::move(elements)};
    }
    if (first == '"') return Json{parse_string()};
    if (consume_word("true")) return Json{true};
    if (consume_word("false")) return Json{false};
    if (consume_word("null")) return Json{nullptr};
    char* end = nullptr;
    const double number = std::strtod(text_.c_str() + position_, &end);
    if (end == text_.c_str() + position_) throw std::runtime_error("bad number");
    position_ = static_cast<std::size_t>(end - text_.c_str());
    return Json{number};
  }

  std::string text_;
  std::size_t position_ = 0;
};

// Runs the reader and returns its parsed stdout; fails the test if the reader rejects the file.
Json run_reader(const std::string& arguments) {
  const std::string command = std::string(kPython) + " '" + kReader.string() + "' " + arguments;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("popen failed");
  std::string output;
  char buffer[4096];
  std::size_t read_count = 0;
  while ((read_count = std::fread(buffer, 1, sizeof buffer, pipe)) > 0) {
    output.append(buffer, read_count);
  }
  const int status = ::pclose(pipe);
  if (status != 0) throw std::runtime_error("reader failed on: " + arguments);
  return JsonParser(output).parse();
}

std::uint64_t bits(double value) {
  return std::bit_cast<std::uint64_t>(value);
}

class VtuWriterTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kPython)) GTEST_SKIP() << kPython << " is missing; cannot run read_vtu.py";
    directory_ = fs::temp_directory_path() /
                 ("rktsph_vtu_test_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(directory_);
    fs::create_directories(directory_);
  }
  void TearDown() override {
    std::error_code ignored;
    if (!directory_.empty()) fs::remove_all(directory_, ignored);
  }

  // Compares a decoded array (interleaved by point) with SoA input, bit for bit.
  static void expect_interleaved(const Json& array, const std::vector<std::vector<double>>& soa) {
    const auto& values = array["values"].array();
    const std::size_t components = soa.size();
    ASSERT_EQ(array["components"].number(), static_cast<double>(components));
    ASSERT_EQ(values.size(), components * soa.front().size());
    for (std::size_t point = 0; point < soa.front().size(); ++point) {
      for (std::size_t component = 0; component < components; ++component) {
        EXPECT_EQ(bits(values[point * components + component].number()),
                  bits(soa[component][point]))
            << "point " << point << " component " << component;
      }
    }
  }

  fs::path directory_;
};

TEST_F(VtuWriterTest, PythonReaderRecoversEveryValueOfA2dCloud) {
  PointCloud cloud;
  cloud.dimension = 2;
  const std::vector<std::array<double, 3>> coordinates = {{0.0, 0.0, 0.0},
                                                          {1.25, -0.5, 0.0},
                                                          {-3.5e-7, 2.0, 0.0},
                                                          {12345.678, 1e-300, 0.0},
                                                          {0.1, -0.0, 0.0}};
  for (const auto& point : coordinates)
    cloud.push_back(point, 1.0);
  // z is deliberately garbage: a 2D writer must ignore it and write zeros.
  cloud.position[2] = {9.0, 9.0, 9.0, 9.0, 9.0};

  const std::vector<double> pressure = {1.25, -3.5e-7, 12345.678, 4.9e-324, -0.0};
  const std::vector<std::vector<double>> velocity = {{1.0, 2.0, 3.0, 4.0, 5.0},
                                                     {-1.5, -2.5, -3.5, -4.5, -5.5},
                                                     {1e10, 1e-10, 0.3, 2.0 / 3.0, -7.0}};
  std::vector<std::vector<double>> stress(9, std::vector<double>(5));
  for (std::size_t component = 0; component < 9; ++component) {
    for (std::size_t point = 0; point < 5; ++point) {
      stress[component][point] = -12345.678 * static_cast<double>(component + 1) +
                                 1.25 * static_cast<double>(point) - 3.5e-7;
    }
  }

  std::vector<PointField> fields;
  fields.push_back({"pressure", 1, {pressure.data()}});
  fields.push_back({"velocity", 3, {velocity[0].data(), velocity[1].data(), velocity[2].data()}});
  PointField stress_field{"stress <total> & \"more\"", 9, {}};
  for (const auto& component : stress)
    stress_field.component_data.push_back(component.data());
  fields.push_back(stress_field);

  const fs::path file = directory_ / "cloud.vtu";
  write_vtu(file, cloud, fields);
  const Json result = run_reader("'" + file.string() + "'");

  EXPECT_EQ(result["header_type"].text(), "UInt64");
  EXPECT_EQ(result["NumberOfPoints"].number(), 5.0);
  EXPECT_EQ(result["NumberOfCells"].number(), 5.0);
  EXPECT_EQ(result["Points"]["type"].text(), "Float64");
  expect_interleaved(result["Points"], {{0.0, 1.25, -3.5e-7, 12345.678, 0.1},
                                        {0.0, -0.5, 2.0, 1e-300, -0.0},
                                        {0.0, 0.0, 0.0, 0.0, 0.0}});
  expect_interleaved(result["PointData"]["pressure"], {pressure});
  expect_interleaved(result["PointData"]["velocity"], velocity);
  expect_interleaved(result["PointData"]["stress <total> & \"more\""], stress);

  // One VTK_VERTEX (type 1) per point, cell i = point i.
  const std::vector<double> connectivity = {0, 1, 2, 3, 4};
  const std::vector<double> offsets = {1, 2, 3, 4, 5};
  const std::vector<double> types = {1, 1, 1, 1, 1};
  EXPECT_EQ(result["Cells"]["connectivity"]["type"].text(), "Int64");
  EXPECT_EQ(result["Cells"]["offsets"]["type"].text(), "Int64");
  EXPECT_EQ(result["Cells"]["types"]["type"].text(), "UInt8");
  expect_interleaved(result["Cells"]["connectivity"], {connectivity});
  expect_interleaved(result["Cells"]["offsets"], {offsets});
  expect_interleaved(result["Cells"]["types"], {types});
}

// ParaView lists a component by its ComponentName<i>; without them a tensor shows as 0..8 where
// the README says to pick XX.
TEST_F(VtuWriterTest, TensorAndVectorComponentsCarryTheNamesParaViewShows) {
  const std::vector<double> x = {0.0, 1.0}, values = {1.0, 2.0};
  const std::vector<PointField> fields = {
      {"pressure", 1, {values.data()}},
      {"velocity", 3, std::vector<const double*>(3, values.data())},
      {"stress", 9, std::vector<const double*>(9, values.data())}};
  const fs::path file = directory_ / "named.vtu";
  write_vtu(file, PointPositions{1, 2, {x.data(), nullptr, nullptr}}, fields);
  const Json result = run_reader("'" + file.string() + "'");
  auto names = [&](const std::string& field) {
    std::string joined;
    for (const Json& name : result["PointData"][field]["component_names"].array())
      joined += (joined.empty() ? "" : " ") +
                (std::holds_alternative<std::string>(name.value) ? name.text() : "-");
    return joined;
  };
  EXPECT_EQ(names("stress"), "XX XY XZ YX YY YZ ZX ZY ZZ");
  EXPECT_EQ(names("velocity"), "X Y Z");
  EXPECT_EQ(names("pressure"), "-");
}

// 1, 2 and 4 points give the three possible base64 tail lengths for the UInt8 types array
// (8 + n bytes), so every padding case goes through the Python decoder.
TEST_F(VtuWriterTest, EveryBase64PaddingCaseDecodes) {
  for (const std::size_t count : {std::size_t{0}, std::size_t{1}, std::size_t{2}, std::size_t{4}}) {
    std::vector<double> x(count), values(count);
    for (std::size_t i = 0; i < count; ++i) {
      x[i] = 0.5 * static_cast<double>(i);
      values[i] = -1.0 / static_cast<double>(i + 3);
    }
    PointPositions positions{1, count, {x.data(), nullptr, nullptr}};
    const std::vector<PointField> fields = {{"f", 1, {values.data()}}};
    const fs::path file = directory_ / ("n" + std::to_string(count) + ".vtu");
    write_vtu(file, positions, fields);
    const Json result = run_reader("'" + file.string() + "'");
    ASSERT_EQ(result["NumberOfPoints"].number(), static_cast<double>(count));
    if (count == 0) continue;
    std::vector<double> zeros(count, 0.0);
    expect_interleaved(result["Points"], {x, zeros, zeros});
    expect_interleaved(result["PointData"]["f"], {values});
  }
}

TEST_F(VtuWriterTest, InconsistentFieldIsRejectedWithoutWritingAFile) {
  std::vector<double> x = {0.0, 1.0};
  PointPositions positions{1, 2, {x.data(), nullptr, nullptr}};
  const std::vector<PointField> wrong_count = {{"v", 3, {x.data(), x.data()}}};
  const fs::path file = directory_ / "bad.vtu";
  EXPECT_THROW(write_vtu(file, positions, wrong_count), std::invalid_argument);
  const std::vector<PointField> null_component = {{"v", 1, {nullptr}}};
  EXPECT_THROW(write_vtu(file, positions, null_component), std::invalid_argument);
  PointPositions missing_y{2, 2, {x.data(), nullptr, nullptr}};
  EXPECT_THROW(write_vtu(file, missing_y, {}), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(directory_));
}

TEST_F(VtuWriterTest, PvdListsFilesInTimeOrderAfterEveryAdd) {
  const fs::path pvd = directory_ / "run.pvd";
  PvdCollection collection(pvd);
  EXPECT_FALSE(fs::exists(pvd));

  collection.add(0.0, "cloud_000000.vtu");
  Json result = run_reader("--pvd '" + pvd.string() + "'");
  ASSERT_EQ(result["datasets"].array().size(), 1u);

  collection.add(2.5e-3, "cloud_000002.vtu");
  // Out of order on purpose: the collection must still be listed by time.
  collection.add(1.0e-3, "cloud_000001.vtu");
  collection.add(0.1, "odd & <name>.vtu");
  result = run_reader("--pvd '" + pvd.string() + "'");
  const auto& datasets = result["datasets"].array();
  const std::vector<std::pair<double, std::string>> expected = {{0.0, "cloud_000000.vtu"},
                                                                {1.0e-3, "cloud_000001.vtu"},
                                                                {2.5e-3, "cloud_000002.vtu"},
                                                                {0.1, "odd & <name>.vtu"}};
  ASSERT_EQ(datasets.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(bits(datasets[i]["timestep"].number()), bits(expected[i].first)) << i;
    EXPECT_EQ(datasets[i]["file"].text(), expected[i].second) << i;
  }

  // Re-adding a file (a rewritten output) moves it instead of listing it twice.
  collection.add(0.2, "cloud_000001.vtu");
  result = run_reader("--pvd '" + pvd.string() + "'");
  ASSERT_EQ(result["datasets"].array().size(), 4u);
  EXPECT_EQ(result["datasets"].array().back()["file"].text(), "cloud_000001.vtu");
  EXPECT_EQ(result["datasets"].array()[1]["file"].text(), "cloud_000002.vtu");
}

// Guards the reader itself: a test that can never fail is worthless, so a corrupted file (one
// byte of the base64 text changed in a way that breaks the length) must be rejected.
TEST_F(VtuWriterTest, ReaderRejectsATruncatedArray) {
  std::vector<double> x = {1.0, 2.0, 3.0};
  PointPositions positions{1, 3, {x.data(), nullptr, nullptr}};
  std::ostringstream out;
  write_vtu(out, positions, {});
  std::string document = out.str();
  const std::string marker = "Name=\"Points\" NumberOfComponents=\"3\" format=\"binary\">";
  const std::size_t data_start = document.find(marker);
  ASSERT_NE(data_start, std::string::npos);
  const std::size_t text_start = document.find_first_not_of(" \n", data_start + marker.size());
  document.erase(text_start, 4);  // drops 3 bytes from the Points array
  const fs::path file = directory_ / "truncated.vtu";
  {
    std::ofstream stream(file);
    stream << document;
  }
  EXPECT_THROW(run_reader("'" + file.string() + "'"), std::runtime_error);
}

}  // namespace
}  // namespace rktsph::vtu_writer_test
