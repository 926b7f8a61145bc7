// docs/input-reference.md against the key declarations of the case reader (case/key_spec.hpp):
// every declared key has one row, with the same type, unit, default and allowed values, and every
// row is a declared key. The rows checked are those of the tables whose header is
// "| key | type | unit | default | allowed | meaning |"; backticks are ignored.
#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "rktsph/case/key_spec.hpp"

namespace rktsph::input_reference_test {
namespace {

const std::string kKeyTableHeader = "| key | type | unit | default | allowed | meaning |";

/// The cells of a Markdown table row, split at '|' but not at "\|", trimmed, backticks removed,
/// "\|" read as '|'.
std::vector<std::string> table_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '\\' && i + 1 < line.size() && line[i + 1] == '|') {
      cell += '|';
      ++i;
    } else if (line[i] == '|') {
      cells.push_back(cell);
      cell.clear();
    } else if (line[i] != '`') {
      cell += line[i];
    }
  }
  for (std::string& text : cells) {
    const std::size_t first = text.find_first_not_of(' ');
    const std::size_t last = text.find_last_not_of(' ');
    text = first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  }
  return cells;
}

struct DocumentedKey {
  std::vector<std::string> cells;  ///< key, type, unit, default, allowed, meaning
  int line = 0;
};

/// The rows of every key table of the document at `path`, by key.
std::map<std::string, std::vector<DocumentedKey>> documented_keys(const std::string& path) {
  std::ifstream stream(path);
  EXPECT_TRUE(stream) << "cannot read " << path;
  std::map<std::string, std::vector<DocumentedKey>> keys;
  std::string line;
  bool in_key_table = false;
  int number = 0;
  while (std::getline(stream, line)) {
    ++number;
    if (line == kKeyTableHeader) {
      in_key_table = true;
      continue;
    }
    if (!in_key_table) continue;
    if (line.rfind("|", 0) != 0) {
      in_key_table = false;
      continue;
    }
    if (line.rfind("|---", 0) == 0) continue;
    const std::vector<std::string> cells = table_cells(line);
    keys[cells.empty() ? std::string() : cells[0]].push_back({cells, number});
  }
  return keys;
}

/// The row the documentation should have for `key`.
std::string expected_row(const DeclaredKey& key) {
  return "| `" + key.path + "` | " + key.type + " | " + key.unit + " | " + key.default_value +
         " | " + key.allowed + " | " + key.doc + " |";
}

void expect_documented_as_declared(const std::vector<DeclaredKey>& declared,
                                   const std::map<std::string, std::vector<DocumentedKey>>& rows) {
  for (const DeclaredKey& key : declared) {
    const auto found = rows.find(key.path);
    if (found == rows.end()) {
      ADD_FAILURE() << "docs/input-reference.md does not list the key '" << key.path
                    << "'; add the row\n"
                    << expected_row(key);
      continue;
    }
    EXPECT_EQ(found->second.size(), 1u) << "'" << key.path << "' is listed more than once";
    const DocumentedKey& row = found->second.front();
    ASSERT_EQ(row.cells.size(), 6u) << "line " << row.line << ": a key row has six cells";
    const std::vector<std::pair<std::string, std::string>> columns = {
        {"type", key.type},
        {"unit", key.unit},
        {"default", key.default_value},
        {"allowed", key.allowed}};
    for (std::size_t c = 0; c < columns.size(); ++c) {
      EXPECT_EQ(row.cells[c + 1], columns[c].second)
          << "docs/input-reference.md line " << row.line << ", key '" << key.path << "': the "
          << columns[c].first << " differs from the declaration; the declared row is\n"
          << expected_row(key);
    }
  }
  for (const auto& [path, documented] : rows) {
    bool is_declared = false;
    for (const DeclaredKey& key : declared)
      is_declared = is_declared || key.path == path;
    EXPECT_TRUE(is_declared) << "docs/input-reference.md line " << documented.front().line
                             << " lists the key '" << path << "', which the reader does not "
                             << "declare";
  }
}

TEST(InputReference, ListsEveryDeclaredKeyAsDeclared) {
  const auto rows = documented_keys(std::string(RKTSPH_SOURCE_DIR) + "/docs/input-reference.md");
  expect_documented_as_declared(declared_case_keys(), rows);
}

TEST(InputReference, CheckFailsForAMissingKeyADifferentDefaultAndAnUndeclaredKey) {
  const std::string path = testing::TempDir() + "input-reference-check.md";
  {
    std::ofstream file(path);
    file << "# Reference\n\n"
         << kKeyTableHeader << "\n|---|---|---|---|---|---|\n"
         << "| `time.end` | number | s | required | > 0 | End time. |\n"
         << "| `time.max_steps` | integer | | 1000 | ≥ 1 | Steps. |\n"
         << "| `time.start` | number | s | 0 | ≥ 0 | Not a key. |\n";
  }
  const std::vector<DeclaredKey> declared = {
      {"time.end", "number", "s", "required", "> 0", "End time of the run."},
      {"time.max_steps", "integer", "", "100000000", "≥ 1", "Steps."},
      {"output.interval", "number", "s", "0", "≥ 0", "Field output."},
  };
  testing::TestPartResultArray failures;
  {
    testing::ScopedFakeTestPartResultReporter reporter(
        testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &failures);
    expect_documented_as_declared(declared, documented_keys(path));
  }
  std::string messages;
  for (int i = 0; i < failures.size(); ++i)
    messages += failures.GetTestPartResult(i).message() + std::string("\n");
  EXPECT_EQ(failures.size(), 3) << messages;
  EXPECT_NE(messages.find("does not list the key 'output.interval'"), std::string::npos);
  EXPECT_NE(messages.find("'time.max_steps': the default differs"), std::string::npos);
  EXPECT_NE(messages.find("lists the key 'time.start'"), std::string::npos);
}

}  // namespace
}  // namespace rktsph::input_reference_test
