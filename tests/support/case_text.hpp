// Small case texts and a locator for tests that read cases: a free 1D bar (no conditions, loads or
// initial conditions, so that a test appends its own sections), and the line of a piece of text,
// found independently of the reader to check the lines of its errors.
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace rktsph::test {

/// A 10 m linear-elastic bar, 21 nodes, nothing acting on it.
inline std::string free_bar() {
  return R"(name: bar
dimension: 1
geometry:
  spacing: 0.5
  shapes: [{segment: [0, 10], material: soil}]
materials:
  soil: {model: linear_elastic, density: 2000, young_modulus: 1.0e8, poisson_ratio: 0.3}
time: {end: 0.01}
)";
}

/// The 1-based line of the first occurrence of `needle` in `text`.
inline int line_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "the text lacks '" << needle << "'";
  int line = 1;
  for (std::size_t i = 0; i < at && i < text.size(); ++i)
    line += text[i] == '\n' ? 1 : 0;
  return line;
}

}  // namespace rktsph::test
