// The citations in the sources and documents of the repository can be followed by whoever clones
// it: every "docs/theory.md §X" or "eq. X" names a heading or a numbered equation that exists in
// docs/theory.md, and nothing cites the documents the project was started from, which are not in
// the repository (the specification, the prototype reports, the seed text, their tags R1–R10 and
// Q1–Q22); docs/theory.md summarises what the code takes from them (chapter 7).
//
// Which document a number belongs to: the nearest document name before it on the same line
// ("theory.md", "thesis", "validation.md", "README", ...). A number with no name before it belongs
// to docs/theory.md in docs/theory.md itself and in source files that cite docs/theory.md, and to
// nothing in the other Markdown files (their tables and headings number thesis sections).

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace theory_references_test {
namespace {

namespace fs = std::filesystem;

const fs::path kRoot = RKTSPH_SOURCE_DIR;

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line);
  return lines;
}

struct TheoryNumbers {
  std::set<std::string> sections;   // "3", "3.4", ...
  std::set<std::string> equations;  // "3.9", "6.2a", ...

  bool has_equation(const std::string& number) const {
    if (equations.count(number)) return true;
    // "eq. 6.2" for the pair (6.2a), (6.2b).
    const auto next = equations.lower_bound(number);
    return next != equations.end() && next->rfind(number, 0) == 0 &&
           next->size() == number.size() + 1 && std::isalpha(next->back());
  }
};

TheoryNumbers read_theory_numbers(const fs::path& theory) {
  static const std::regex heading(R"(^#{2,4}\s+(\d+(?:\.\d+)*)\.?\s)");
  static const std::regex equation(R"(\((\d+\.\d+[a-z]?)\)\s*$)");
  TheoryNumbers numbers;
  for (const std::string& line : read_lines(theory)) {
    std::smatch match;
    if (std::regex_search(line, match, heading)) numbers.sections.insert(match[1]);
    if (std::regex_search(line, match, equation)) numbers.equations.insert(match[1]);
  }
  return numbers;
}

/// The files whose citations are checked: sources, tests, tools and the documents.
std::vector<fs::path> checked_files() {
  std::vector<fs::path> files;
  for (const char* folder : {"src", "tests", "app", "bench", "fuzz", "tools", "cases", "docs"}) {
    const fs::path root = kRoot / folder;
    if (!fs::exists(root)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
      if (!entry.is_regular_file()) continue;
      const fs::path& path = entry.path();
      const std::string extension = path.extension().string();
      const bool text = extension == ".cpp" || extension == ".hpp" || extension == ".py" ||
                        extension == ".md" || extension == ".sh";
      if (text && path.filename() != "theory_references_test.cpp") files.push_back(path);
    }
  }
  files.push_back(kRoot / "README.md");
  std::sort(files.begin(), files.end());
  return files;
}

/// The nearest document name before `position` on the line, lower case; "" if none.
std::string cited_document(const std::string& line, std::size_t position) {
  static const std::vector<std::string> kNames = {"theory.md", "thesis",  "validation.md",
                                                  "readme",    "section", "appendix"};
  std::string lower = line.substr(0, position);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::string nearest;
  std::size_t nearest_at = 0;
  for (const std::string& name : kNames) {
    const std::size_t at = lower.rfind(name);
    if (at != std::string::npos && (nearest.empty() || at > nearest_at)) {
      nearest = name;
      nearest_at = at;
    }
  }
  return nearest;
}

struct Finding {
  std::string where;  // file:line
  std::string what;
};

std::string repository_path(const fs::path& path) {
  return fs::relative(path, kRoot).generic_string();
}

/// Citations of docs/theory.md sections and equations that do not exist there.
std::vector<Finding> unresolved_theory_references(const TheoryNumbers& theory) {
  // "§3.4", "§1.3–1.4" (the end of a range is checked too); "eq. 2.5", "eqs. 3.5–3.8".
  static const std::regex section(R"(§\s?(\d+(?:\.\d+)*)(?:\s?–\s?(\d+(?:\.\d+)*))?)");
  static const std::regex equation(
      R"(\b[Ee]qs?\.\s?\(?(\d+\.\d+[a-z]?)\)?(?:\s?–\s?\(?(\d+\.\d+[a-z]?)\)?)?)");
  std::vector<Finding> findings;
  for (const fs::path& file : checked_files()) {
    const std::vector<std::string> lines = read_lines(file);
    const bool is_theory =
        file.filename() == "theory.md" && file.parent_path().filename() == "docs";
    const bool is_markdown = file.extension() == ".md";
    bool cites_theory = is_theory;
    for (const std::string& line : lines)
      cites_theory = cites_theory || line.find("theory.md") != std::string::npos;
    if (!cites_theory) continue;
    for (std::size_t n = 0; n < lines.size(); ++n) {
      const std::string& line = lines[n];
      const auto check = [&](const std::regex& pattern, bool is_section) {
        for (auto it = std::sregex_iterator(line.begin(), line.end(), pattern);
             it != std::sregex_iterator(); ++it) {
          const std::string document = cited_document(line, it->position(0));
          if (!document.empty() && document != "theory.md") continue;
          if (document.empty() && is_markdown && !is_theory) continue;
          for (int group = 1; group <= 2; ++group) {
            if (!(*it)[group].matched) continue;
            const std::string number = (*it)[group];
            const bool exists =
                is_section ? theory.sections.count(number) > 0 : theory.has_equation(number);
            if (!exists)
              findings.push_back(
                  {repository_path(file) + ":" + std::to_string(n + 1),
                   std::string(is_section ? "§" : "eq. ") + number + " in: " + line});
          }
        }
      };
      check(section, true);
      check(equation, false);
    }
  }
  return findings;
}

/// Citations of documents that are not in the repository.
std::vector<Finding> external_citations() {
  struct Pattern {
    std::regex regex;
    bool in_theory;  // also looked for in docs/theory.md, which defines the R and Q tags (§7)
  };
  const auto icase = std::regex::ECMAScript | std::regex::icase;
  static const std::vector<Pattern> kPatterns = {
      {std::regex(R"(\bspec(ification)?('s)?\s*(§|Q\d|eq|algorithm|validation|/))", icase), true},
      {std::regex(R"(\bthe spec('s)?\b)", icase), true},
      {std::regex(R"(algorithm\.md|prototype-findings|prototype-vpw|findings\.md|v2-research)",
                  icase),
       true},
      {std::regex(R"(\bprototype( finding)?s? (R\d|§))", icase), true},
      {std::regex(R"(\bseed('s)?\s+(eqs?\.|§|TOC))", icase), true},
      {std::regex(R"(\bthe seed's\b)", icase), true},
      {std::regex(R"(shared/(spec|seed|reference|bench))", icase), true},
      {std::regex(R"((^|[^/])\bvalidation\.md)", icase), true},
      {std::regex(R"(\[(GUESS|REC|SEED|LIT|CHK)\]|validation\.md \[R\])", icase), true},
      {std::regex(R"(\bR(10|[1-9])\b)"), false},
      {std::regex(R"(\bQ(1\d|2[0-2]|[1-9])\b)"), false},
  };
  std::vector<Finding> findings;
  for (const fs::path& file : checked_files()) {
    const bool is_theory =
        file.filename() == "theory.md" && file.parent_path().filename() == "docs";
    const std::vector<std::string> lines = read_lines(file);
    for (std::size_t n = 0; n < lines.size(); ++n)
      for (const Pattern& pattern : kPatterns)
        if ((pattern.in_theory || !is_theory) && std::regex_search(lines[n], pattern.regex)) {
          findings.push_back({repository_path(file) + ":" + std::to_string(n + 1), lines[n]});
          break;
        }
  }
  return findings;
}

std::string describe(const std::vector<Finding>& findings) {
  std::string text;
  for (const Finding& finding : findings)
    text += "\n  " + finding.where + ": " + finding.what;
  return text;
}

TEST(TheoryReferences, TheoryHasItsNumberedSectionsAndEquations) {
  const TheoryNumbers theory = read_theory_numbers(kRoot / "docs" / "theory.md");
  EXPECT_TRUE(theory.sections.count("2.2"));
  EXPECT_TRUE(theory.sections.count("6.3"));
  EXPECT_FALSE(theory.sections.count("2.3"));
  EXPECT_TRUE(theory.has_equation("2.5"));
  EXPECT_TRUE(theory.has_equation("3.9"));
  EXPECT_TRUE(theory.has_equation("6.2"));  // (6.2a), (6.2b)
  EXPECT_FALSE(theory.has_equation("6.20"));
}

TEST(TheoryReferences, EveryCitedSectionAndEquationExists) {
  const TheoryNumbers theory = read_theory_numbers(kRoot / "docs" / "theory.md");
  const std::vector<Finding> findings = unresolved_theory_references(theory);
  EXPECT_TRUE(findings.empty()) << findings.size()
                                << " citations of docs/theory.md that do not resolve:"
                                << describe(findings);
}

TEST(TheoryReferencesSlow, NothingCitesADocumentOutsideTheRepository) {
  const std::vector<Finding> findings = external_citations();
  EXPECT_TRUE(findings.empty()) << findings.size()
                                << " lines cite documents that are not in the repository (cite "
                                   "docs/theory.md instead):"
                                << describe(findings);
}

}  // namespace
}  // namespace theory_references_test
