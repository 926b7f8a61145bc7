// The located YAML layer: positions, paths, typed reads and --set overrides. Expected lines and
// columns are counted by hand from the small texts below (1-based).
#include "rktsph/case/yaml_reader.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rktsph::yaml_reader_test {
namespace {

const std::string kText =
    "# comment line\n"     // 1
    "alpha: 1.5\n"         // 2
    "beta:\n"              // 3
    "  gamma: [1, 2]\n"    // 4
    "  delta: \"text\"\n"  // 5
    "list:\n"              // 6
    "  - {a: 1}\n"         // 7
    "  - b\n"              // 8
    "empty:\n";            // 9

/// Runs `action` and returns the InputError it throws; fails the test if it throws none.
template <typename Action>
InputError catch_input_error(Action action) {
  try {
    action();
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError(SourceLocation{}, "", "", "", "");
}

TEST(YamlReader, NodesKnowTheirPathsAndOneBasedLocations) {
  const YamlNode root = parse_yaml(kText, "t.yaml");
  ASSERT_TRUE(root.is_map());
  const YamlNode* alpha = root.find("alpha");
  ASSERT_NE(alpha, nullptr);
  EXPECT_EQ(alpha->text, "1.5");
  EXPECT_EQ(alpha->path, "alpha");
  EXPECT_EQ(alpha->key_where.line, 2);
  EXPECT_EQ(alpha->key_where.column, 1);
  EXPECT_EQ(alpha->where.line, 2);
  EXPECT_EQ(alpha->where.column, 8);
  EXPECT_EQ(alpha->where.file, "t.yaml");

  const YamlNode& gamma = *root.find("beta")->find("gamma");
  EXPECT_EQ(gamma.path, "beta.gamma");
  ASSERT_TRUE(gamma.is_sequence());
  EXPECT_EQ(gamma.children[1].path, "beta.gamma.1");
  EXPECT_EQ(gamma.children[1].where.line, 4);
  EXPECT_EQ(gamma.children[1].where.column, 14);

  const YamlNode& list = *root.find("list");
  EXPECT_EQ(list.children[0].find("a")->path, "list.0.a");
  EXPECT_EQ(list.children[1].text, "b");
  EXPECT_EQ(list.children[1].where.line, 8);
}

TEST(YamlReader, EmptyValueIsLocatedAtItsKey) {
  const YamlNode root = parse_yaml(kText, "t.yaml");
  const YamlNode& empty = *root.find("empty");
  EXPECT_TRUE(empty.is_null());
  EXPECT_EQ(empty.where.line, 9);
}

TEST(YamlReader, SyntaxErrorIsReportedAtItsLine) {
  const InputError error =
      catch_input_error([] { parse_yaml("a: 1\nb: [1, 2\nc: 3\n", "bad.yaml"); });
  EXPECT_EQ(error.location().file, "bad.yaml");
  EXPECT_GE(error.location().line, 2);  // the open bracket is on line 2; yaml-cpp may see it later
  EXPECT_LE(error.location().line, 3);
  EXPECT_NE(std::string(error.what()).find("syntax"), std::string::npos);
}

TEST(YamlReader, DuplicateKeyIsAnErrorAtTheSecondOne) {
  const InputError error = catch_input_error([] { parse_yaml("a: 1\nb: 2\na: 3\n", "d.yaml"); });
  EXPECT_EQ(error.location().line, 3);
  EXPECT_EQ(error.key(), "a");
  EXPECT_NE(error.problem().find("duplicate"), std::string::npos);
}

TEST(YamlReader, NumbersInYamlNotations) {
  const YamlNode root =
      parse_yaml("a: 1e8\nb: 2.0e-3\nc: 100\nd: -.5\ne: +3\nf: 1.5E+2\n", "n.yaml");
  EXPECT_EQ(to_number(*root.find("a")), 1e8);
  EXPECT_EQ(to_number(*root.find("b")), 2.0e-3);
  EXPECT_EQ(to_number(*root.find("c")), 100.0);
  EXPECT_EQ(to_number(*root.find("d")), -0.5);
  EXPECT_EQ(to_number(*root.find("e")), 3.0);
  EXPECT_EQ(to_number(*root.find("f")), 150.0);
}

TEST(YamlReader, NonNumbersAndNonFiniteNumbersAreRejected) {
  const YamlNode root = parse_yaml(
      "nan: .nan\ninf: -.inf\nword: abc\nquoted: \"5\"\nlist: [1]\nhuge: 1e999\nhex: 0x10\n",
      "n.yaml");
  for (const char* key : {"nan", "inf", "word", "quoted", "list", "huge", "hex"}) {
    const InputError error = catch_input_error([&] { to_number(*root.find(key)); });
    EXPECT_EQ(error.key(), key);
    EXPECT_EQ(error.location().line, root.find(key)->where.line) << key;
  }
}

TEST(YamlReader, RangesAreCheckedAndDescribed) {
  const YamlNode root = parse_yaml("zero: 0\nhalf: 0.5\n", "r.yaml");
  const NumberRange open_low{0.0, 1.5, true, false};
  EXPECT_EQ(open_low.describe(), "a number in (0, 1.5]");
  EXPECT_EQ(NumberRange::positive().describe(), "a number > 0");
  EXPECT_EQ(NumberRange::non_negative().describe(), "a number >= 0");
  EXPECT_EQ(to_number(*root.find("half"), open_low), 0.5);
  const InputError error = catch_input_error([&] { to_number(*root.find("zero"), open_low); });
  EXPECT_EQ(error.allowed(), "a number in (0, 1.5]");
  EXPECT_EQ(error.value(), "0");
  EXPECT_EQ(to_number(*root.find("zero"), NumberRange::non_negative()), 0.0);
}

TEST(YamlReader, IntegersMayBeWrittenInExponentNotationButNotAsFractions) {
  const YamlNode root = parse_yaml("a: 1e6\nb: 2.5\nc: 0\n", "i.yaml");
  EXPECT_EQ(to_integer(*root.find("a"), 1, 10000000), 1000000);
  catch_input_error([&] { to_integer(*root.find("b"), 0, 10); });
  catch_input_error([&] { to_integer(*root.find("c"), 1, 10); });
}

TEST(YamlReader, BooleansAreOnlyTrueAndFalse) {
  const YamlNode root = parse_yaml("a: true\nb: False\nc: yes\nd: \"true\"\n", "b.yaml");
  EXPECT_TRUE(to_bool(*root.find("a")));
  EXPECT_FALSE(to_bool(*root.find("b")));
  catch_input_error([&] { to_bool(*root.find("c")); });
  catch_input_error([&] { to_bool(*root.find("d")); });
}

TEST(YamlReader, ClosestMatchWithinTwoEdits) {
  const std::vector<std::string> keys = {"spacing", "shapes", "courant", "time_step"};
  EXPECT_EQ(closest_match("spaceing", keys), "spacing");     // one insertion
  EXPECT_EQ(closest_match("corant", keys), "courant");       // one deletion
  EXPECT_EQ(closest_match("tiem_step", keys), "time_step");  // two substitutions
  EXPECT_EQ(closest_match("spacing_x", keys), "spacing");    // two insertions
  EXPECT_EQ(closest_match("spacing_xy", keys), "");          // three insertions
  EXPECT_EQ(closest_match("zz", keys), "");
}

TEST(YamlMap, UnknownKeyGivesSuggestionAndList) {
  const YamlNode root = parse_yaml("outer:\n  spacng: 1\n", "u.yaml");
  const YamlMap outer(*root.find("outer"));
  const InputError error = catch_input_error([&] { outer.allow_only({"spacing", "shapes"}); });
  EXPECT_EQ(error.location().line, 2);
  EXPECT_EQ(error.location().column, 3);
  EXPECT_EQ(error.key(), "outer.spacng");
  EXPECT_NE(error.problem().find("did you mean 'spacing'?"), std::string::npos);
  EXPECT_EQ(error.allowed(), "'spacing' or 'shapes'");
}

TEST(YamlMap, MissingKeyIsReportedAtTheEnclosingMapsKey) {
  const YamlNode root = parse_yaml("a: 1\nouter:\n  x: 1\n", "m.yaml");
  const YamlMap outer(*root.find("outer"));
  const InputError error = catch_input_error([&] { outer.require("spacing"); });
  EXPECT_EQ(error.location().line, 2);
  EXPECT_EQ(error.key(), "outer.spacing");
  EXPECT_TRUE(error.value().empty());
}

TEST(YamlMap, ExactlyOneOf) {
  const YamlNode root = parse_yaml("two: {p: 1, q: 2}\nnone: {r: 1}\n", "o.yaml");
  const InputError both = catch_input_error([&] {
    YamlMap(*root.find("two")).require_one_of({"p", "q"});
  });
  EXPECT_EQ(both.key(), "two.q");
  catch_input_error([&] { YamlMap(*root.find("none")).require_one_of({"p", "q"}); });
}

TEST(YamlMap, WrongTypeIsReportedAtTheValue) {
  const YamlNode root = parse_yaml("a:\n  - 1\n", "w.yaml");
  const InputError error = catch_input_error([&] { YamlMap map(*root.find("a")); });
  EXPECT_EQ(error.location().line, 2);
  EXPECT_NE(error.problem().find("a list"), std::string::npos);
}

TEST(YamlOverride, ReplacesAValueAndKeepsTheKeyLocation) {
  YamlNode root = parse_yaml("a:\n  b: 1\n", "f.yaml");
  apply_override(root, "a.b", "[2, 3]");
  const YamlNode& b = *root.find("a")->find("b");
  ASSERT_TRUE(b.is_sequence());
  EXPECT_EQ(b.children[1].text, "3");
  EXPECT_EQ(b.children[1].path, "a.b.1");
  EXPECT_EQ(b.key_where.line, 2);
  EXPECT_EQ(b.where.file, "<--set a.b=[2, 3]>");
  EXPECT_EQ(b.children[0].where.file, "<--set a.b=[2, 3]>");
}

TEST(YamlOverride, CreatesMissingMapsAndAppendsListItems) {
  YamlNode root = parse_yaml("list:\n  - x: 1\n", "f.yaml");
  apply_override(root, "new.inner.value", "5");
  apply_override(root, "list.1.x", "2");
  apply_override(root, "fresh.0.name", "p");
  EXPECT_EQ(root.find("new")->find("inner")->find("value")->text, "5");
  EXPECT_TRUE(root.find("new")->key_from_override);
  ASSERT_EQ(root.find("list")->children.size(), 2u);
  EXPECT_EQ(root.find("list")->children[1].find("x")->text, "2");
  ASSERT_TRUE(root.find("fresh")->is_sequence());
  EXPECT_EQ(root.find("fresh")->children[0].find("name")->path, "fresh.0.name");
}

TEST(YamlOverride, BadPathsAreReportedAgainstTheSetOption) {
  YamlNode root = parse_yaml("list: [1]\nscalar: 2\n", "f.yaml");
  for (const char* key : {"list.5", "list.name", "scalar.x"}) {
    const InputError error = catch_input_error([&] { apply_override(root, key, "1"); });
    EXPECT_EQ(error.location().file, "<--set>") << key;
    EXPECT_EQ(error.key(), key);
  }
  const InputError syntax = catch_input_error([&] { apply_override(root, "scalar", "[1, "); });
  EXPECT_EQ(syntax.location().file, "<--set scalar=[1, >");
}

TEST(YamlOverride, AnAddedKeyOutsideTheAllowedListIsABadPath) {
  YamlNode root = parse_yaml("numerics:\n  courant: 0.5\n", "f.yaml");
  apply_override(root, "numerics.tme_step", "1e-4");
  const InputError error = catch_input_error([&] {
    YamlMap(*root.find("numerics")).allow_only({"courant", "time_step"});
  });
  EXPECT_EQ(error.location().file, "<--set>");
  EXPECT_EQ(error.value(), "numerics.tme_step=1e-4");
  EXPECT_NE(error.problem().find("did you mean 'time_step'?"), std::string::npos);
}

TEST(YamlReader, RenderValueIsShortAndFlow) {
  const YamlNode root = parse_yaml("a: {min: [0, 0], max: [1, 2]}\n", "r.yaml");
  EXPECT_EQ(render_value(*root.find("a")), "{min: [0, 0], max: [1, 2]}");
}

/// "Billion laughs": ten levels of ten aliases each, 10^10 values once expanded, in under 1 KB.
std::string nested_alias_document() {
  std::string text = "a0: &a0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level < 10; ++level) {
    const std::string name = std::to_string(level);
    text.append("a").append(name).append(": &a").append(name).append(" [");
    for (int i = 0; i < 10; ++i)
      text.append(i > 0 ? ", *a" : "*a").append(std::to_string(level - 1));
    text += "]\n";
  }
  return text + "name: *a9\n";
}

TEST(YamlReader, NestedAliasesAreRefusedBeforeTheyAreExpanded) {
  const std::string text = nested_alias_document();
  ASSERT_LT(text.size(), 1024u);
  const InputError error = catch_input_error([&] { parse_yaml(text, "bomb.yaml"); });
  EXPECT_EQ(error.location().file, "bomb.yaml");
  // a4 is the first key whose expanded value (10^5 + 1 values) passes the limit of 10^5.
  EXPECT_EQ(error.location().line, 5);
  EXPECT_EQ(error.key(), "a4");
  EXPECT_NE(error.problem().find("more than 100000 values"), std::string::npos) << error.what();
  EXPECT_NE(error.allowed().find("at most 100000"), std::string::npos);
}

TEST(YamlReader, AliasesWithinTheLimitAreExpanded) {
  const YamlNode root = parse_yaml("base: &b {density: 2000}\ncopy: *b\n", "a.yaml");
  const YamlNode* copy = root.find("copy");
  ASSERT_NE(copy, nullptr);
  ASSERT_NE(copy->find("density"), nullptr);
  EXPECT_EQ(copy->find("density")->text, "2000");
  EXPECT_EQ(copy->find("density")->path, "copy.density");
}

TEST(YamlOverride, NestedAliasesInASetValueAreRefused) {
  YamlNode root = parse_yaml("a: 1\n", "f.yaml");
  std::string flow = "[&x0 [y, y, y, y, y, y, y, y, y, y]";
  for (int level = 1; level < 6; ++level) {
    flow.append(", &x").append(std::to_string(level)).append(" [");
    for (int i = 0; i < 10; ++i)
      flow.append(i > 0 ? ", *x" : "*x").append(std::to_string(level - 1));
    flow += "]";
  }
  flow += "]";
  const InputError error = catch_input_error([&] { apply_override(root, "a", flow); });
  EXPECT_EQ(error.location().file.rfind("<--set a=", 0), 0u) << error.what();
}

}  // namespace
}  // namespace rktsph::yaml_reader_test
