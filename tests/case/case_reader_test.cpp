// The case reader against its schema (docs/input-reference.md).
//
// Expected values are the ones written in the fixtures (tests/data/cases) or the defaults listed in
// the schema; expected error positions are found by searching the case text for the offending
// token, independently of the reader.
#include "rktsph/case/case_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "rktsph/case/computed_defaults.hpp"

namespace rktsph::case_reader_test {
namespace {

constexpr const char* kFile = "case.yaml";

std::string fixture_path(const std::string& name) {
  // Fixtures sit next to the tests: <tests>/data/cases, with this file in <tests>/case.
  return (std::filesystem::path(__FILE__).parent_path().parent_path() / "data" / "cases" / name)
      .string();
}

std::string read_fixture(const std::string& name) {
  std::ifstream stream(fixture_path(name));
  if (!stream) throw std::runtime_error("missing fixture " + fixture_path(name));
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

/// `text` with the first `from` replaced by `to`; throws if `from` is absent, so that a fixture
/// edit cannot silently turn a test into one that checks nothing.
std::string replace_once(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at == std::string::npos) throw std::runtime_error("fixture lacks '" + from + "'");
  return text.replace(at, from.size(), to);
}

struct Position {
  int line = 0;
  int column = 0;
};

/// 1-based line and column of the first occurrence of `needle` in `text`.
Position position_of(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) throw std::runtime_error("text lacks '" + needle + "'");
  Position position{1, 1};
  for (std::size_t i = 0; i < at; ++i) {
    if (text[i] == '\n') {
      ++position.line;
      position.column = 1;
    } else {
      ++position.column;
    }
  }
  return position;
}

/// How the reader names a polygon edge in its messages.
std::string fmt_edge(int index, const std::string& from, const std::string& to, int line) {
  return "edge " + std::to_string(index) + " (" + from + " to " + to + ", line " +
         std::to_string(line) + ")";
}

InputError read_error(const std::string& text, const std::vector<CaseOverride>& overrides = {}) {
  try {
    read_case_text(text, kFile, overrides);
  } catch (const InputError& error) {
    return error;
  }
  ADD_FAILURE() << "expected an InputError";
  return InputError(SourceLocation{}, "", "", "", "");
}

// ------------------------------------------------------------------------------------------------
// Valid input: values and defaults

TEST(CaseReader, MinimalCaseGetsTheSchemaDefaults) {
  const CaseDescription description = read_case_file(fixture_path("bar1d_minimal.yaml"));
  EXPECT_EQ(description.name, "bar1d-minimal");
  EXPECT_EQ(description.file, fixture_path("bar1d_minimal.yaml"));
  EXPECT_EQ(description.description, "");
  EXPECT_EQ(description.model, ModelKind::DrySolid);
  EXPECT_EQ(description.dimension, 1);
  EXPECT_EQ(description.plane, PlaneKind::Strain);
  EXPECT_EQ(description.geometry.spacing, 0.5);
  ASSERT_EQ(description.geometry.shapes.size(), 1u);
  EXPECT_EQ(description.geometry.shapes[0].kind, ShapeSpec::Kind::Segment);
  EXPECT_EQ(description.geometry.shapes[0].vertices[0][0], 0.0);
  EXPECT_EQ(description.geometry.shapes[0].vertices[1][0], 10.0);
  EXPECT_EQ(description.geometry.shapes[0].material, "soil");
  const ParameterBlock& soil = description.materials.at("soil");
  EXPECT_EQ(soil.path, "materials.soil");
  EXPECT_EQ(soil.words.at("model").first, "linear_elastic");
  EXPECT_EQ(soil.values.at("young_modulus").value, 1.0e8);
  EXPECT_EQ(soil.values.at("density").value, 2000.0);
  EXPECT_EQ(soil.values.at("poisson_ratio").value, 0.3);

  // Built-in groups of 1D only.
  ASSERT_EQ(description.groups.size(), 3u);
  EXPECT_EQ(description.groups[0].name, "all");
  EXPECT_EQ(description.groups[0].kind, GroupSpec::Kind::All);
  EXPECT_EQ(description.groups[1].name, "xmin");
  EXPECT_EQ(description.groups[1].edge, "xmin");
  EXPECT_EQ(description.groups[2].name, "xmax");

  EXPECT_TRUE(description.boundary_conditions.empty());
  EXPECT_FALSE(description.gravity.has_value());
  EXPECT_FALSE(description.damping.has_value());
  EXPECT_EQ(description.initial.velocity, (Vec3{0.0, 0.0, 0.0}));
  EXPECT_FALSE(description.initial.geostatic_surface.has_value());

  const NumericsSpec& numerics = description.numerics;
  EXPECT_EQ(numerics.kernel, KernelType::CubicSpline);
  EXPECT_EQ(numerics.h_over_dx, 0.75);
  EXPECT_EQ(numerics.interpolation_order, 0);
  EXPECT_EQ(numerics.courant, 0.5);
  EXPECT_FALSE(numerics.time_step.has_value());
  EXPECT_TRUE(numerics.frozen_flux_source);
  EXPECT_EQ(numerics.rk_substep_factor, 0.5);
  EXPECT_EQ(numerics.rk_max_substeps, 1000);
  EXPECT_TRUE(numerics.hourglass_filter);
  EXPECT_EQ(numerics.hourglass_kappa, 0.1);
  EXPECT_EQ(numerics.hourglass_h_over_dx, 1.3);
  EXPECT_FALSE(numerics.hourglass_fields.has_value());  // from the stencil width
  EXPECT_EQ(numerics.artificial_viscosity, 0.0);

  EXPECT_EQ(description.time.end, 0.36);
  EXPECT_EQ(description.time.max_steps, 100000000);
  EXPECT_EQ(description.output.interval, 0.0);
  EXPECT_EQ(description.output.probe_interval, 0.0);
  EXPECT_TRUE(description.output.fields.empty());
  EXPECT_TRUE(description.probes.empty());
}

TEST(CaseReader, RichCaseReadsEveryValueAsWritten) {
  const std::string text = read_fixture("rich2d.yaml");
  const CaseDescription description = read_case_text(text, kFile);
  EXPECT_EQ(description.description, "Embankment with a weak zone: all keys in use");
  EXPECT_EQ(description.model, ModelKind::SaturatedVpw);
  EXPECT_EQ(description.dimension, 2);
  EXPECT_EQ(description.plane, PlaneKind::Stress);

  const auto& shapes = description.geometry.shapes;
  ASSERT_EQ(shapes.size(), 2u);
  EXPECT_EQ(shapes[0].kind, ShapeSpec::Kind::Polygon);
  ASSERT_EQ(shapes[0].vertices.size(), 6u);
  EXPECT_EQ(shapes[0].vertices[4], (Vec3{10.0, 15.0, 0.0}));
  EXPECT_EQ(shapes[1].kind, ShapeSpec::Kind::Rectangle);
  EXPECT_EQ(shapes[1].vertices[0], (Vec3{4.0, 2.0, 0.0}));
  EXPECT_EQ(shapes[1].vertices[1], (Vec3{6.0, 3.5, 0.0}));
  EXPECT_EQ(shapes[1].material, "weak");
  EXPECT_EQ(shapes[1].where.line, position_of(text, "- rectangle").line);

  // Material parameters keep where they were written, for the material factory's errors.
  const ParameterBlock& weak = description.materials.at("weak");
  EXPECT_EQ(weak.words.at("model").first, "perzyna_von_mises");
  EXPECT_EQ(weak.values.at("yield_stress").value, 15000.0);
  const Position yield_value = position_of(text, "15000");
  EXPECT_EQ(weak.values.at("yield_stress").where.line, yield_value.line);
  EXPECT_EQ(weak.values.at("yield_stress").where.column, yield_value.column);
  EXPECT_EQ(weak.where.line, position_of(text, "  weak:").line);

  // Built-ins (all, xmin, xmax, ymin, ymax) then the four defined groups in file order.
  ASSERT_EQ(description.groups.size(), 9u);
  EXPECT_EQ(description.groups[3].name, "ymin");
  EXPECT_EQ(description.groups[5].name, "base");
  EXPECT_EQ(description.groups[5].kind, GroupSpec::Kind::Edge);
  EXPECT_EQ(description.groups[5].edge, "ymin");
  EXPECT_EQ(description.groups[6].kind, GroupSpec::Kind::Box);
  EXPECT_EQ(description.groups[6].min, (Vec3{4.9, 0.0, 0.0}));
  EXPECT_EQ(description.groups[6].max, (Vec3{5.1, 1.0, 0.0}));
  EXPECT_EQ(description.groups[7].kind, GroupSpec::Kind::Polygon);
  EXPECT_EQ(description.groups[7].vertices.size(), 3u);
  EXPECT_EQ(description.groups[8].kind, GroupSpec::Kind::Point);
  EXPECT_EQ(description.groups[8].point, (Vec3{5.0, 15.0, 0.0}));

  const auto& conditions = description.boundary_conditions;
  ASSERT_EQ(conditions.size(), 7u);
  EXPECT_EQ(conditions[0].kind, BoundaryConditionSpec::Kind::Fixed);
  EXPECT_EQ(conditions[0].group, "base");
  EXPECT_EQ(conditions[1].kind, BoundaryConditionSpec::Kind::Roller);
  EXPECT_EQ(conditions[1].axis, 0);
  EXPECT_TRUE(conditions[1].mirror);
  EXPECT_FALSE(conditions[2].mirror);
  EXPECT_EQ(conditions[3].kind, BoundaryConditionSpec::Kind::Velocity);
  ASSERT_TRUE(conditions[3].velocity[0].has_value());
  const TimeFunction& wave = *conditions[3].velocity[0];
  EXPECT_EQ(wave.kind, TimeFunction::Kind::Harmonic);
  EXPECT_EQ(wave.amplitude, 0.2);
  EXPECT_EQ(wave.period, 0.5);
  EXPECT_EQ(wave.phase, 0.1);
  EXPECT_EQ(wave.offset, 0.05);
  EXPECT_EQ(wave.start, 0.01);
  EXPECT_EQ(conditions[3].velocity[1]->kind, TimeFunction::Kind::Constant);
  EXPECT_EQ(conditions[3].velocity[1]->value, -0.1);
  EXPECT_EQ(conditions[4].kind, BoundaryConditionSpec::Kind::Traction);
  EXPECT_FALSE(conditions[4].traction[0].has_value());
  EXPECT_EQ(conditions[4].traction[1]->kind, TimeFunction::Kind::LinearRamp);
  EXPECT_EQ(conditions[4].traction[1]->value, -10000.0);
  EXPECT_EQ(conditions[4].traction[1]->start, 0.02);
  EXPECT_EQ(conditions[4].traction[1]->duration, 0.05);
  EXPECT_EQ(conditions[5].traction[0]->kind, TimeFunction::Kind::Step);
  EXPECT_EQ(conditions[5].traction[0]->start, 0.3);
  EXPECT_EQ(conditions[5].traction[1]->kind, TimeFunction::Kind::Constant);
  EXPECT_EQ(conditions[5].traction[1]->value, -2.0);
  const TimeFunction& table = *conditions[6].velocity[1];
  EXPECT_EQ(table.kind, TimeFunction::Kind::Table);
  ASSERT_EQ(table.table.size(), 3u);
  EXPECT_EQ(table.table[2], (std::pair<double, double>{0.3, -0.5}));

  ASSERT_TRUE(description.gravity.has_value());
  EXPECT_EQ(description.gravity->acceleration, (Vec3{0.0, -9.81, 0.0}));
  EXPECT_EQ(description.gravity->factor.kind, TimeFunction::Kind::LinearRamp);
  EXPECT_EQ(description.gravity->factor.duration, 0.5);
  ASSERT_TRUE(description.damping.has_value());
  EXPECT_EQ(description.damping->coefficient, 20.0);
  EXPECT_EQ(description.damping->start, 0.1);
  EXPECT_EQ(description.damping->end, 2.0);

  EXPECT_EQ(description.initial.velocity, (Vec3{0.5, -0.25, 0.0}));
  EXPECT_EQ(description.initial.geostatic_surface, 10.0);
  EXPECT_EQ(description.initial.k0, 0.43);

  const NumericsSpec& numerics = description.numerics;
  EXPECT_EQ(numerics.kernel, KernelType::QuinticSpline);
  EXPECT_EQ(numerics.h_over_dx, 1.2);
  EXPECT_EQ(numerics.interpolation_order, 1);
  EXPECT_EQ(numerics.courant, 0.3);
  EXPECT_EQ(numerics.time_step, 1.0e-4);
  EXPECT_FALSE(numerics.frozen_flux_source);
  EXPECT_EQ(numerics.rk_substep_factor, 3.5);
  EXPECT_EQ(numerics.rk_max_substeps, 200);
  EXPECT_FALSE(numerics.hourglass_filter);
  EXPECT_EQ(numerics.hourglass_kappa, 0.2);
  EXPECT_EQ(numerics.hourglass_h_over_dx, 1.5);
  EXPECT_EQ(numerics.hourglass_fields, HourglassFields::All);
  EXPECT_EQ(numerics.artificial_viscosity, 0.5);

  EXPECT_EQ(description.time.end, 2.5);
  EXPECT_EQ(description.time.max_steps, 500000);  // written as 5e5
  EXPECT_EQ(description.output.interval, 0.01);
  EXPECT_EQ(description.output.probe_interval, 0.001);
  EXPECT_EQ(description.output.fields,
            (std::vector<std::string>{"velocity", "stress", "pore_pressure"}));
  ASSERT_EQ(description.probes.size(), 2u);
  EXPECT_EQ(description.probes[0].name, "mid");
  EXPECT_EQ(description.probes[0].group, "window");
  EXPECT_EQ(description.probes[0].fields, (std::vector<std::string>{"stress_xx", "velocity_x"}));
  EXPECT_EQ(description.probes[0].reduction, ProbeSpec::Reduction::MaxAbs);
  EXPECT_EQ(description.probes[1].reduction, ProbeSpec::Reduction::Mean);
}

TEST(CaseReader, OneDimensionalVectorsMayBeScalars) {
  std::string text = read_fixture("bar1d_minimal.yaml");
  text +=
      "groups:\n  tip: {point: 10.0}\n  near: {point: [9.5]}\n"
      "initial_conditions:\n  velocity: 0.25\n";
  const CaseDescription description = read_case_text(text, kFile);
  EXPECT_EQ(description.groups[3].point[0], 10.0);
  EXPECT_EQ(description.groups[4].point[0], 9.5);
  EXPECT_EQ(description.initial.velocity[0], 0.25);
}

// ------------------------------------------------------------------------------------------------
// Errors

struct Misspelling {
  std::string original;    ///< text in rich2d.yaml
  std::string misspelt;    ///< replacement, beginning with the misspelt key
  std::string key_path;    ///< expected dotted key of the error
  std::string suggestion;  ///< expected "did you mean"
};

// Names the parameter in failure messages instead of dumping its bytes.
void PrintTo(const Misspelling& typo, std::ostream* stream) {
  *stream << typo.key_path;
}

class MisspeltKey : public testing::TestWithParam<Misspelling> {};

TEST_P(MisspeltKey, IsReportedAtItsLineWithASuggestion) {
  const Misspelling& typo = GetParam();
  const std::string text = replace_once(read_fixture("rich2d.yaml"), typo.original, typo.misspelt);
  const InputError error = read_error(text);
  const std::string bad_key = typo.key_path.substr(typo.key_path.rfind('.') + 1);
  const Position expected = position_of(text, bad_key + ":");
  EXPECT_EQ(error.location().file, kFile);
  EXPECT_EQ(error.location().line, expected.line) << error.what();
  EXPECT_EQ(error.location().column, expected.column) << error.what();
  EXPECT_EQ(error.key(), typo.key_path);
  const std::string message = error.what();
  EXPECT_NE(message.find(std::string(kFile) + ":" + std::to_string(expected.line)),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("'" + bad_key + "'"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean '" + typo.suggestion + "'?"), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    EveryLevel, MisspeltKey,
    testing::Values(
        Misspelling{"dimension: 2", "dimenson: 2", "dimenson", "dimension"},
        Misspelling{"spacing: 0.25", "spacng: 0.25", "geometry.spacng", "spacing"},
        Misspelling{"material: weak", "materail: weak", "geometry.shapes.1.materail", "material"},
        Misspelling{"courant: 0.3", "courrant: 0.3", "numerics.courrant", "courant"},
        Misspelling{"enabled: false", "enabeld: false", "numerics.hourglass.enabeld", "enabled"},
        Misspelling{"duration: 0.05}}", "duraton: 0.05}}",
                    "boundary_conditions.4.traction.y.duraton", "duration"},
        Misspelling{"coefficient: 20", "coeficient: 20", "loads.damping.coeficient", "coefficient"},
        Misspelling{"k0: 0.43", "k_0: 0.43", "initial_conditions.geostatic.k_0", "k0"},
        Misspelling{"{box: {min", "{bx: {min", "groups.window.bx", "box"},
        Misspelling{"reduction: max_abs", "reductoin: max_abs", "probes.0.reductoin", "reduction"},
        Misspelling{"max_steps: 5e5", "max_step: 5e5", "time.max_step", "max_steps"},
        Misspelling{"probe_interval: 0.001", "probe_intervall: 0.001", "output.probe_intervall",
                    "probe_interval"}));

TEST(CaseReader, NegativeSpacingIsReportedAtTheValueWithTheRange) {
  const std::string text =
      replace_once(read_fixture("bar1d_minimal.yaml"), "spacing: 0.5", "spacing: -0.5");
  const InputError error = read_error(text);
  const Position value = position_of(text, "-0.5");
  EXPECT_EQ(error.location().line, value.line);
  EXPECT_EQ(error.location().column, value.column);
  EXPECT_EQ(error.key(), "geometry.spacing");
  EXPECT_EQ(error.value(), "-0.5");
  EXPECT_EQ(error.allowed(), "a number > 0");
}

TEST(CaseReader, RangeLimitsAreOpenOrClosedAsSpecified) {
  const std::string base = read_fixture("bar1d_minimal.yaml");
  const auto with_numerics = [&base](const std::string& entry) {
    return base + "numerics:\n  " + entry + "\n";
  };
  // Accepted edges.
  EXPECT_EQ(read_case_text(with_numerics("courant: 1"), kFile).numerics.courant, 1.0);
  EXPECT_EQ(read_case_text(with_numerics("h_over_dx: 3"), kFile).numerics.h_over_dx, 3.0);
  EXPECT_EQ(read_case_text(with_numerics("hourglass: {kappa: 0}"), kFile).numerics.hourglass_kappa,
            0.0);
  const NumericsSpec controls =
      read_case_text(with_numerics("hourglass: {stiffness: 1, strain_stiffness: 0}"), kFile)
          .numerics;
  EXPECT_EQ(controls.hourglass_stiffness.value_or(0.0), 1.0);
  EXPECT_EQ(controls.strain_hourglass_stiffness, 0.0);
  // Rejected edges and beyond, each at the value's line with the range in `allowed`.
  const std::vector<std::pair<std::string, std::string>> rejected = {
      {"courant: 0", "(0, 1]"},
      {"courant: 1.01", "(0, 1]"},
      {"h_over_dx: 0.5", "(0.5, 3]"},
      {"hourglass: {kappa: 1.01}", "[0, 1]"},
      {"rk_max_substeps: 0", "[1, "},
      {"interpolation_order: 2", "[0, 1]"},
      {"time_step: 0", "> 0"},
      {"artificial_viscosity: -1", ">= 0"},
      {"rk_substep_factor: 0", "> 0"},
      {"hourglass: {stiffness: 1.5}", "[0, 1]"},
      {"hourglass: {strain_stiffness: -0.1}", "[0, 1]"}};
  for (const auto& [entry, range] : rejected) {
    const std::string text = with_numerics(entry);
    const InputError error = read_error(text);
    EXPECT_EQ(error.location().line, position_of(text, entry).line) << entry;
    EXPECT_NE(error.allowed().find(range), std::string::npos) << entry << ": " << error.what();
  }
  const std::string no_end = replace_once(base, "end: 0.36", "end: 0");
  EXPECT_EQ(read_error(no_end).key(), "time.end");
}

TEST(CaseReader, CheckerboardStabilisationIsReadAndANegativeValueRejected) {
  const std::string base = read_fixture("rich2d.yaml");
  const std::string entry = "  solver_tolerance: 1.0e-9\n";
  EXPECT_EQ(read_case_text(base, kFile).pore_fluid->checkerboard_stabilisation, 0.0);  // default
  const std::string on = replace_once(base, entry, entry + "  checkerboard_stabilisation: 0.3\n");
  EXPECT_EQ(read_case_text(on, kFile).pore_fluid->checkerboard_stabilisation, 0.3);
  const std::string text =
      replace_once(base, entry, entry + "  checkerboard_stabilisation: -0.1\n");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "pore_fluid.checkerboard_stabilisation");
  EXPECT_EQ(error.location().line, position_of(text, "checkerboard_stabilisation:").line);
  EXPECT_NE(error.allowed().find(">= 0"), std::string::npos) << error.what();
}

TEST(CaseReader, HourglassFieldsAcceptsVelocityOrAllOnly) {
  const std::string base = read_fixture("bar1d_minimal.yaml") + "numerics:\n  hourglass: ";
  EXPECT_EQ(read_case_text(base + "{fields: velocity}\n", kFile).numerics.hourglass_fields,
            HourglassFields::Velocity);
  const std::string text = base + "{fields: stress}\n";
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "numerics.hourglass.fields");
  EXPECT_EQ(error.location().line, position_of(text, "fields:").line);
  EXPECT_NE(error.allowed().find("velocity"), std::string::npos) << error.what();
  EXPECT_NE(error.allowed().find("all"), std::string::npos) << error.what();
}

TEST(CaseReader, NotANumberOrInfinityIsRejected) {
  for (const char* value : {".nan", ".inf", "-.Inf", "NaN"}) {
    const std::string text = replace_once(read_fixture("bar1d_minimal.yaml"), "density: 2000",
                                          std::string("density: ") + value);
    const InputError error = read_error(text);
    EXPECT_EQ(error.key(), "materials.soil.density") << value;
    EXPECT_EQ(error.location().line, position_of(text, "density:").line) << value;
  }
}

TEST(CaseReader, SyntaxErrorGivesTheLine) {
  const std::string text = replace_once(read_fixture("bar1d_minimal.yaml"), "segment: [0.0, 10.0]",
                                        "segment: [0.0, 10.0");
  const InputError error = read_error(text);
  EXPECT_EQ(error.location().file, kFile);
  // yaml-cpp notices the missing bracket at the unexpected token that follows it: the next line.
  const int bracket_line = position_of(text, "segment:").line;
  EXPECT_GE(error.location().line, bracket_line);
  EXPECT_LE(error.location().line, bracket_line + 1);
  EXPECT_NE(error.problem().find("syntax"), std::string::npos);
}

TEST(CaseReader, MissingRequiredKeyIsReportedAtTheEnclosingMap) {
  const std::string base = read_fixture("bar1d_minimal.yaml");
  struct Case {
    std::string from, to, key, enclosing;
  };
  const std::vector<Case> cases = {
      {"  spacing: 0.5\n", "", "geometry.spacing", "geometry:"},
      {"      material: soil\n", "", "geometry.shapes.0.material", "- segment"},
      {"    model: linear_elastic\n", "", "materials.soil.model", "  soil:"},
      {"  end: 0.36\n", "  max_steps: 10\n", "time.end", "time:"},
  };
  for (const Case& test : cases) {
    const std::string text = replace_once(base, test.from, test.to);
    const InputError error = read_error(text);
    EXPECT_EQ(error.key(), test.key) << error.what();
    EXPECT_EQ(error.location().line, position_of(text, test.enclosing).line) << error.what();
    EXPECT_TRUE(error.value().empty());
    EXPECT_NE(error.problem().find("missing"), std::string::npos);
  }
  // A missing top-level key is reported in the file (at the first key of the document).
  const InputError no_name = read_error(replace_once(base, "name: bar1d-minimal\n", ""));
  EXPECT_EQ(no_name.key(), "name");
  EXPECT_EQ(no_name.location().file, kFile);
}

TEST(CaseReader, WrongTypesAreReportedAtTheValue) {
  const std::string base = read_fixture("bar1d_minimal.yaml");
  struct Case {
    std::string from, to, key, value_token;
  };
  const std::vector<Case> cases = {
      {"density: 2000", "density: \"2000\"", "materials.soil.density", "\"2000\""},
      {"spacing: 0.5", "spacing: [0.5]", "geometry.spacing", "[0.5]"},
      {"end: 0.36", "end: soon", "time.end", "soon"},
      {"dimension: 1", "dimension: {d: 1}", "dimension", "{d: 1}"},
      {"  shapes:\n    - segment: [0.0, 10.0]\n      material: soil\n",
       "  shapes: {segment: [0.0, 10.0], material: soil}\n", "geometry.shapes", "{segment"},
      {"time:\n  end: 0.36", "time: [0.36]", "time", "[0.36]"},
  };
  for (const Case& test : cases) {
    const std::string text = replace_once(base, test.from, test.to);
    const InputError error = read_error(text);
    EXPECT_EQ(error.key(), test.key) << error.what();
    const Position value = position_of(text, test.value_token);
    EXPECT_EQ(error.location().line, value.line) << error.what();
    EXPECT_EQ(error.location().column, value.column) << error.what();
  }
}

TEST(CaseReader, ReferencesMustNameDefinedThings) {
  const std::string base = read_fixture("rich2d.yaml");
  const InputError group = read_error(replace_once(base, "group: base", "group: bse"));
  EXPECT_EQ(group.key(), "boundary_conditions.0.group");
  EXPECT_EQ(group.value(), "bse");
  EXPECT_NE(group.problem().find("did you mean 'base'?"), std::string::npos);

  const InputError probe_group =
      read_error(replace_once(base, "group: crest, fields", "group: nowhere, fields"));
  EXPECT_EQ(probe_group.key(), "probes.1.group");

  const InputError material = read_error(replace_once(base, "material: weak", "material: wek"));
  EXPECT_EQ(material.key(), "geometry.shapes.1.material");
  EXPECT_NE(material.problem().find("did you mean 'weak'?"), std::string::npos);

  // Built-in groups may be referred to without a definition, but not redefined.
  const std::string redefined_text =
      replace_once(base, "  base: {edge: ymin}", "  xmin: {edge: ymin}");
  const InputError redefined = read_error(redefined_text);
  EXPECT_EQ(redefined.key(), "groups.xmin");
  EXPECT_EQ(redefined.location().line, position_of(redefined_text, "  xmin: {edge").line);
}

TEST(CaseReader, DuplicateNamesAreErrors) {
  const std::string base = read_fixture("rich2d.yaml");
  const std::string groups_text =
      replace_once(base, "  crest: {point", "  zone: {point: [1, 1]}\n  crest: {point");
  const InputError group = read_error(groups_text);
  EXPECT_EQ(group.key(), "groups.zone");
  EXPECT_EQ(group.location().line, position_of(groups_text, "  zone: {point").line);

  const InputError probe = read_error(replace_once(base, "{name: top", "{name: mid"));
  EXPECT_EQ(probe.key(), "probes.1.name");

  const InputError field =
      read_error(replace_once(base, "[velocity, stress, pore_pressure]", "[velocity, velocity]"));
  EXPECT_EQ(field.key(), "output.fields.1");
}

TEST(CaseReader, DimensionDependentKeys) {
  const std::string one_d = read_fixture("bar1d_minimal.yaml");
  const std::string two_d = read_fixture("rich2d.yaml");
  struct Case {
    std::string base, from, to, key, at;  ///< `at`: text on the line the error must point to
  };
  const std::vector<Case> cases = {
      {one_d, "dimension: 1", "dimension: 1\nplane: strain", "plane", "plane:"},
      {two_d, "- rectangle: {min: [4, 2], max: [6, 3.5]}", "- segment: [4, 6]",
       "geometry.shapes.1.segment", "segment:"},
      {one_d, "- segment: [0.0, 10.0]", "- rectangle: {min: [0], max: [1]}",
       "geometry.shapes.0.rectangle", "rectangle:"},
      {two_d, "velocity: [0.5, -0.25]", "velocity: [0.5, -0.25, 0]", "initial_conditions.velocity",
       "[0.5, -0.25, 0]"},
      {two_d, "crest: {point: [5.0, 15.0]}", "crest: {point: 5.0}", "groups.crest.point", "crest:"},
      {one_d, "time:", "groups:\n  low: {edge: ymin}\ntime:", "groups.low.edge", "low:"},
      {one_d, "time:", "boundary_conditions:\n  - {group: xmin, roller: y}\ntime:",
       "boundary_conditions.0.roller", "roller: y"},
      {one_d, "time:", "boundary_conditions:\n  - {group: xmax, velocity: {y: 1}}\ntime:",
       "boundary_conditions.0.velocity.y", "{y: 1}"},
      {one_d, "time:", "loads:\n  gravity: {acceleration: [0, -9.81]}\ntime:",
       "loads.gravity.acceleration", "acceleration:"},
  };
  for (const Case& test : cases) {
    const std::string text = replace_once(test.base, test.from, test.to);
    const InputError error = read_error(text);
    EXPECT_EQ(error.key(), test.key) << error.what();
    EXPECT_EQ(error.location().line, position_of(text, test.at).line) << error.what();
  }
}

TEST(CaseReader, ADimensionTheModelDoesNotSupportNamesTheModelsDimensions) {
  for (const std::string model : {"dry_solid", "saturated_vpw"}) {
    const std::string text = replace_once(read_fixture("bar1d_minimal.yaml"), "dimension: 1",
                                          "model: " + model + "\ndimension: 3");
    const InputError error = read_error(text);
    EXPECT_EQ(error.key(), "dimension") << error.what();
    EXPECT_EQ(error.value(), "3") << error.what();
    EXPECT_EQ(error.location().file, kFile);
    EXPECT_EQ(error.location().line, position_of(text, "dimension: 3").line) << error.what();
    EXPECT_EQ(error.problem(), "the model '" + model + "' does not support 3D") << error.what();
    EXPECT_EQ(error.allowed(), "1 or 2 with model: " + model) << error.what();
  }
  // Beyond three, the plain range.
  const InputError error =
      read_error(replace_once(read_fixture("bar1d_minimal.yaml"), "dimension: 1", "dimension: 4"));
  EXPECT_EQ(error.allowed(), "an integer in [1, 3]") << error.what();
}

TEST(CaseReader, ShapeAndBoundaryConditionChoicesAreExclusive) {
  const std::string base = read_fixture("rich2d.yaml");
  const InputError two_shapes = read_error(replace_once(
      base, "- rectangle: {min: [4, 2], max: [6, 3.5]}",
      "- rectangle: {min: [4, 2], max: [6, 3.5]}\n      polygon: [[0, 0], [1, 0], [0, 1]]"));
  EXPECT_EQ(two_shapes.key(), "geometry.shapes.1.polygon");
  const InputError two_kinds =
      read_error(replace_once(base, "    fixed: true", "    fixed: true\n    roller: x"));
  EXPECT_EQ(two_kinds.key(), "boundary_conditions.0.roller");
  const InputError mirror_without_roller =
      read_error(replace_once(base, "    fixed: true", "    fixed: true\n    mirror: false"));
  EXPECT_EQ(mirror_without_roller.key(), "boundary_conditions.0.mirror");
  const InputError not_fixed = read_error(replace_once(base, "fixed: true", "fixed: false"));
  EXPECT_EQ(not_fixed.key(), "boundary_conditions.0.fixed");
  const InputError reversed = read_error(replace_once(base, "max: [6, 3.5]", "max: [6, 1.5]"));
  EXPECT_EQ(reversed.key(), "geometry.shapes.1.rectangle.max");
  const InputError flat_polygon =
      read_error(replace_once(base, "zone: {polygon: [[0, 0], [1, 0], [0, 1]]}",
                              "zone: {polygon: [[0, 0], [1, 1], [2, 2]]}"));
  EXPECT_EQ(flat_polygon.key(), "groups.zone.polygon");
}

TEST(CaseReader, TimeFunctionsAreValidated) {
  const std::string base = read_fixture("rich2d.yaml");
  struct Case {
    std::string from, to, key;
  };
  const std::vector<Case> cases = {
      {"start: 0.02, duration: 0.05", "start: 0.02, duration: 0",
       "boundary_conditions.4.traction.y.duration"},
      {"[[0, 0], [0.1, 1.5], [0.3, -0.5]]", "[[0, 0], [0.1, 1.5], [0.1, -0.5]]",
       "boundary_conditions.6.velocity.y.points.2.0"},
      {"[[0, 0], [0.1, 1.5], [0.3, -0.5]]", "[[0, 0]]", "boundary_conditions.6.velocity.y.points"},
      {"period: 0.5", "period: -0.5", "boundary_conditions.3.velocity.x.period"},
      {"function: harmonic", "function: harmonik", "boundary_conditions.3.velocity.x.function"},
      {"{function: step, value: 500, start: 0.3}", "{function: step, value: 500, duration: 1}",
       "boundary_conditions.5.traction.x.duration"},
      {"{function: constant, value: -2}", "{function: constant}",
       "boundary_conditions.5.traction.y.value"},
      {"{x: {function: harmonic", "{x: [1, 2], z: {function: harmonic",
       "boundary_conditions.3.velocity.z"},
  };
  for (const Case& test : cases) {
    const InputError error = read_error(replace_once(base, test.from, test.to));
    EXPECT_EQ(error.key(), test.key) << error.what();
  }
  const InputError misspelt_function =
      read_error(replace_once(base, "function: harmonic", "function: harmonik"));
  EXPECT_NE(misspelt_function.problem().find("did you mean 'harmonic'?"), std::string::npos);
}

// ------------------------------------------------------------------------------------------------
// Overrides

TEST(CaseOverrides, ParseSplitsAtTheFirstEqualsSign) {
  const CaseOverride parsed = parse_override("loads.gravity.acceleration=[0, -9.81]");
  EXPECT_EQ(parsed.key, "loads.gravity.acceleration");
  EXPECT_EQ(parsed.value, "[0, -9.81]");
  EXPECT_EQ(parse_override("description=a=b").value, "a=b");
  for (const char* bad : {"no-equals", "=5", "a..b=1", ".a=1", "a.=1"}) {
    try {
      parse_override(bad);
      ADD_FAILURE() << bad;
    } catch (const InputError& error) {
      EXPECT_EQ(error.location().file, "<--set>") << bad;
    }
  }
}

TEST(CaseOverrides, ChangeAndAddValues) {
  const std::string base = read_fixture("bar1d_minimal.yaml");
  const CaseDescription description = read_case_text(
      base, kFile,
      {parse_override("geometry.spacing=0.25"), parse_override("numerics.time_step=2e-5"),
       parse_override("boundary_conditions.0.group=xmax"),
       parse_override("boundary_conditions.0.velocity={x: -0.1}"),
       parse_override("materials.soil.density=1800"), parse_override("geometry.spacing=0.125")});
  EXPECT_EQ(description.geometry.spacing, 0.125);  // later overrides win
  EXPECT_EQ(description.numerics.time_step, 2e-5);
  ASSERT_EQ(description.boundary_conditions.size(), 1u);
  EXPECT_EQ(description.boundary_conditions[0].group, "xmax");
  EXPECT_EQ(description.boundary_conditions[0].velocity[0]->value, -0.1);
  EXPECT_EQ(description.materials.at("soil").values.at("density").value, 1800.0);
  EXPECT_EQ(description.materials.at("soil").values.at("density").where.file,
            "<--set materials.soil.density=1800>");
}

TEST(CaseOverrides, ListItemsByIndex) {
  const std::string base = read_fixture("rich2d.yaml");
  const CaseDescription description =
      read_case_text(base, kFile,
                     {parse_override("boundary_conditions.1.roller=y"),
                      parse_override("probes.0.fields=[velocity_y]")});
  EXPECT_EQ(description.boundary_conditions[1].axis, 1);
  EXPECT_EQ(description.probes[0].fields, std::vector<std::string>{"velocity_y"});
}

TEST(CaseOverrides, PathOutsideTheSchemaIsReportedAgainstTheOption) {
  const std::string base = read_fixture("bar1d_minimal.yaml");
  for (const char* text : {"numerics.courrant=0.3", "geometry.spacing.x=1", "numerik.courant=1",
                           "geometry.shapes.3.material=soil"}) {
    const InputError error = read_error(base, {parse_override(text)});
    EXPECT_EQ(error.location().file, "<--set>") << text << ": " << error.what();
    EXPECT_NE(std::string(error.what()).find(text), std::string::npos) << error.what();
  }
  const InputError typo = read_error(base, {parse_override("numerics.courrant=0.3")});
  EXPECT_NE(typo.problem().find("did you mean 'courant'?"), std::string::npos);
}

TEST(CaseOverrides, BadValueIsReportedAgainstTheOverride) {
  const std::string base = read_fixture("bar1d_minimal.yaml");
  const InputError range = read_error(base, {parse_override("numerics.courant=2")});
  EXPECT_EQ(range.location().file, "<--set numerics.courant=2>");
  EXPECT_EQ(range.location().line, 0);
  EXPECT_EQ(range.key(), "numerics.courant");
  EXPECT_EQ(range.allowed(), "a number in (0, 1]");
  const InputError type = read_error(base, {parse_override("geometry.spacing=fine")});
  EXPECT_EQ(type.location().file, "<--set geometry.spacing=fine>");
  const InputError syntax = read_error(base, {parse_override("geometry.spacing=[1")});
  EXPECT_EQ(syntax.location().file, "<--set geometry.spacing=[1>");
  const InputError dimension = read_error(base, {parse_override("plane=stress")});
  EXPECT_EQ(dimension.location().file, "<--set plane=stress>");
}

TEST(CaseReader, ADirectoryIsNotReportedAsAnEmptyCase) {
  const std::string directory = std::filesystem::temp_directory_path().string();
  try {
    read_case_file(directory);
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().file, directory);
    EXPECT_NE(error.problem().find("is a directory"), std::string::npos) << error.what();
  }
}

TEST(CaseReader, AFileThatCannotBeOpenedGivesTheSystemReason) {
  try {
    read_case_file((std::filesystem::temp_directory_path() / "rktsph-no-such-case.yaml").string());
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_NE(error.problem().find("No such file or directory"), std::string::npos) << error.what();
  }
}

// ------------------------------------------------------------------------------------------------
// Several mistakes in one pass

TEST(CaseReader, SeveralMistakesAreReportedTogetherInFileOrder) {
  // Read in the order materials, geometry, time; written geometry (line 5) first.
  std::string text = read_fixture("bar1d_minimal.yaml");
  text = replace_once(text, "young_modulus: 1.0e8", "young_modulus: stiff");
  text = replace_once(text, "spacing: 0.5", "spacing: -0.5");
  text = replace_once(text, "end: 0.36", "end: 0");
  const InputError error = read_error(text);
  const std::vector<InputError> all = error.errors();
  ASSERT_EQ(all.size(), 3u) << error.what();
  EXPECT_EQ(all[0].key(), "geometry.spacing");
  EXPECT_EQ(all[0].location().line, position_of(text, "-0.5").line);
  EXPECT_EQ(all[1].key(), "materials.soil.young_modulus");
  EXPECT_EQ(all[1].location().line, position_of(text, "stiff").line);
  EXPECT_EQ(all[2].key(), "time.end");
  EXPECT_EQ(all[2].location().line, position_of(text, "end: 0").line);
  // The error itself is the first; its message lists all three, one per line, in that order.
  EXPECT_EQ(error.key(), "geometry.spacing");
  const std::string message = error.what();
  EXPECT_EQ(message.rfind("3 errors:\n", 0), 0u) << message;
  const std::size_t spacing = message.find("geometry.spacing");
  const std::size_t modulus = message.find("young_modulus");
  const std::size_t end = message.find("time.end");
  EXPECT_LT(spacing, modulus);
  EXPECT_LT(modulus, end);
  EXPECT_NE(end, std::string::npos);
}

TEST(CaseReader, EveryUnknownKeyOfAMapIsReported) {
  std::string text = read_fixture("bar1d_minimal.yaml");
  text = replace_once(text, "time:\n  end: 0.36", "time:\n  end: 0.36\n  ned: 1\n  max_step: 5");
  const std::vector<InputError> all = read_error(text).errors();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].key(), "time.ned");
  EXPECT_EQ(all[1].key(), "time.max_step");
}

TEST(CaseReader, AnUnknownKeyDoesNotHideABadValueBesideIt) {
  std::string text = read_fixture("bar1d_minimal.yaml");
  text = replace_once(text, "time:\n  end: 0.36", "time:\n  end: -1\n  ned: 1");
  const std::vector<InputError> all = read_error(text).errors();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].key(), "time.end");
  EXPECT_EQ(all[1].key(), "time.ned");
}

TEST(CaseReader, AReportListsAtMostTwentyMistakesAndCountsTheRest) {
  std::string text = read_fixture("bar1d_minimal.yaml");
  for (int i = 0; i < 25; ++i)
    text += "unknown_" + std::to_string(i) + ": 1\n";
  const InputError error = read_error(text);
  EXPECT_EQ(error.errors().size(), 25u);
  const std::string message = error.what();
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 21) << message;
  EXPECT_NE(message.find("\nand 5 more"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown_19"), std::string::npos);
  EXPECT_EQ(message.find("unknown_20"), std::string::npos);
}

TEST(CaseReader, AGroupInErrorIsNotReportedAgainWhereItIsUsed) {
  std::string text = read_fixture("rich2d.yaml");
  text = replace_once(text, "crest: {point: [5.0, 15.0]}", "crest: {point: [5.0, high]}");
  const std::vector<InputError> all = read_error(text).errors();
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].location().line, position_of(text, "high").line);
}

TEST(CaseOverrides, ErrorsOfSetArgumentsFollowTheFileAndNameTheArgument) {
  std::string text = read_fixture("bar1d_minimal.yaml");
  text = replace_once(text, "spacing: 0.5", "spacing: -0.5");
  const InputError error = read_error(text, {parse_override("time.end=-1")});
  const std::vector<InputError> all = error.errors();
  ASSERT_EQ(all.size(), 2u) << error.what();
  EXPECT_EQ(all[0].location().file, kFile);
  EXPECT_EQ(all[1].location().file, "<--set time.end=-1>");
  EXPECT_NE(std::string(error.what()).find("<--set time.end=-1>: error: key 'time.end'"),
            std::string::npos)
      << error.what();
}

TEST(CaseOverrides, AProbeFieldKeepsTheLocationOfItsSetArgument) {
  const std::string base = read_fixture("rich2d.yaml");
  const CaseDescription description =
      read_case_text(base, kFile, {parse_override("probes.0.fields.1=strss")});
  ASSERT_EQ(description.probes[0].field_where.size(), 2u);
  EXPECT_EQ(description.probes[0].field_where[0].line, position_of(base, "stress_xx").line);
  EXPECT_EQ(description.probes[0].field_where[1].file, "<--set probes.0.fields.1=strss>");
  EXPECT_EQ(description.probes[0].path, "probes.0");
}

// ------------------------------------------------------------------------------------------------
// Polygons

TEST(CaseReader, SelfIntersectingPolygonIsRefusedNamingTheCrossingEdges) {
  const std::string base = read_fixture("rich2d.yaml");
  // Non-zero area (150), but edge 1 ([20, 0] to [0, 15]) crosses edge 3 ([10, 15] to [0, 0]).
  const std::string text =
      replace_once(base, "polygon: [[0, 0], [20, 0], [20, 10], [10, 10], [10, 15], [0, 15]]",
                   "polygon: [[0, 0], [20, 0], [0, 15], [10, 15]]");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "geometry.shapes.0.polygon");
  const int line = position_of(text, "[[0, 0], [20, 0], [0, 15]").line;
  EXPECT_EQ(error.location().line, line);
  EXPECT_NE(error.problem().find("intersects itself"), std::string::npos) << error.what();
  EXPECT_NE(error.problem().find(fmt_edge(1, "[20, 0]", "[0, 15]", line)), std::string::npos)
      << error.what();
  EXPECT_NE(error.problem().find(fmt_edge(3, "[10, 15]", "[0, 0]", line)), std::string::npos)
      << error.what();
}

// A symmetric bow-tie has zero signed area (its two loops cancel), but what is wrong with it is
// the crossing, and that is what the user must be told.
TEST(CaseReader, ABowTiePolygonIsCalledSelfIntersectingNotZeroArea) {
  const std::string base = read_fixture("rich2d.yaml");
  const std::string text =
      replace_once(base, "polygon: [[0, 0], [20, 0], [20, 10], [10, 10], [10, 15], [0, 15]]",
                   "polygon: [[0, 0], [20, 10], [20, 0], [0, 10]]");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "geometry.shapes.0.polygon");
  EXPECT_NE(error.problem().find("intersects itself"), std::string::npos) << error.what();
  EXPECT_EQ(error.problem().find("zero area"), std::string::npos) << error.what();
}

// Vertices all on one line do not cross; they still have zero area, and are named so.
TEST(CaseReader, APolygonOnOneLineHasZeroArea) {
  const std::string base = read_fixture("rich2d.yaml");
  const std::string text = replace_once(base, "zone: {polygon: [[0, 0], [1, 0], [0, 1]]}",
                                        "zone: {polygon: [[0, 0], [1, 1], [3, 3]]}");
  const InputError error = read_error(text);
  EXPECT_NE(error.problem().find("zero area"), std::string::npos) << error.what();
}

TEST(CaseReader, PolygonGroupThatFoldsBackOnItselfIsRefused) {
  const std::string base = read_fixture("rich2d.yaml");
  // Edges 0 and 1 run along one line and overlap: zero width there, non-zero area elsewhere.
  const std::string text = replace_once(base, "zone: {polygon: [[0, 0], [1, 0], [0, 1]]}",
                                        "zone: {polygon: [[0, 0], [2, 0], [1, 0], [0, 1]]}");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "groups.zone.polygon");
  EXPECT_NE(error.problem().find("intersects itself"), std::string::npos) << error.what();
}

TEST(CaseReader, PolygonWithARepeatedVertexIsRefused) {
  const std::string base = read_fixture("rich2d.yaml");
  const std::string text =
      replace_once(base, "polygon: [[0, 0], [20, 0], [20, 10], [10, 10], [10, 15], [0, 15]]",
                   "polygon: [[0, 0], [20, 0], [20, 10], [20, 0], [10, 15], [0, 15]]");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "geometry.shapes.0.polygon.3");
  EXPECT_NE(error.problem().find("vertex 3 repeats vertex 1"), std::string::npos) << error.what();
}

// ------------------------------------------------------------------------------------------------
// Cells: lattice or triangles (docs/theory.md §3.6)

TEST(CaseReader, CellsAreALatticeByDefaultAndTrianglesOnRequest) {
  const std::string base = read_fixture("rich2d.yaml");
  EXPECT_EQ(read_case_text(base, kFile).geometry.cells, CellLayout::Lattice);
  const std::string text =
      replace_once(base, "  spacing: 0.25\n", "  spacing: 0.25\n  cells: triangles\n");
  const CaseDescription description = read_case_text(text, kFile);
  EXPECT_EQ(description.geometry.cells, CellLayout::Triangles);
  // Written back, and read again the same.
  const std::string written = write_case_yaml(description);
  EXPECT_NE(written.find("cells: triangles"), std::string::npos) << written;
  EXPECT_EQ(read_case_text(written, "written.yaml").geometry.cells, CellLayout::Triangles);
  EXPECT_NE(write_case_yaml(read_case_text(base, kFile)).find("cells: lattice"), std::string::npos);
}

TEST(CaseReader, AnUnknownCellLayoutIsRefusedWithTheWordsAllowed) {
  const std::string text = replace_once(read_fixture("rich2d.yaml"), "  spacing: 0.25\n",
                                        "  spacing: 0.25\n  cells: hexagons\n");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "geometry.cells") << error.what();
  EXPECT_EQ(error.value(), "hexagons") << error.what();
  EXPECT_EQ(error.location().file, kFile);
  EXPECT_EQ(error.location().line, position_of(text, "cells: hexagons").line) << error.what();
  EXPECT_NE(error.allowed().find("lattice"), std::string::npos) << error.what();
  EXPECT_NE(error.allowed().find("triangles"), std::string::npos) << error.what();
}

TEST(CaseReader, TriangleCellsIn1DAreRefused) {
  const std::string text = replace_once(read_fixture("bar1d_minimal.yaml"), "  spacing: 0.5\n",
                                        "  spacing: 0.5\n  cells: triangles\n");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "geometry.cells") << error.what();
  EXPECT_EQ(error.location().line, position_of(text, "cells: triangles").line) << error.what();
  EXPECT_NE(error.problem().find("2D"), std::string::npos) << error.what();
  // The lattice is fine in 1D, said or not.
  EXPECT_EQ(read_case_text(replace_once(read_fixture("bar1d_minimal.yaml"), "  spacing: 0.5\n",
                                        "  spacing: 0.5\n  cells: lattice\n"),
                           kFile)
                .geometry.cells,
            CellLayout::Lattice);
}

TEST(CaseReader, APolygonThatIsNotSimpleStaysAnErrorWithTriangleCells) {
  const std::string base = replace_once(read_fixture("rich2d.yaml"), "  spacing: 0.25\n",
                                        "  spacing: 0.25\n  cells: triangles\n");
  const std::string text =
      replace_once(base, "polygon: [[0, 0], [20, 0], [20, 10], [10, 10], [10, 15], [0, 15]]",
                   "polygon: [[0, 0], [20, 0], [0, 15], [10, 15]]");
  const InputError error = read_error(text);
  EXPECT_EQ(error.key(), "geometry.shapes.0.polygon");
  EXPECT_EQ(error.location().line, position_of(text, "[[0, 0], [20, 0], [0, 15]").line);
  EXPECT_NE(error.problem().find("intersects itself"), std::string::npos) << error.what();
}

// ------------------------------------------------------------------------------------------------
// Writing

void expect_same_function(const TimeFunction& a, const TimeFunction& b, const std::string& what) {
  EXPECT_EQ(a.kind, b.kind) << what;
  EXPECT_EQ(a.value, b.value) << what;
  EXPECT_EQ(a.start, b.start) << what;
  EXPECT_EQ(a.duration, b.duration) << what;
  EXPECT_EQ(a.table, b.table) << what;
  EXPECT_EQ(a.amplitude, b.amplitude) << what;
  EXPECT_EQ(a.period, b.period) << what;
  EXPECT_EQ(a.phase, b.phase) << what;
  EXPECT_EQ(a.offset, b.offset) << what;
}

void expect_same_components(const std::array<std::optional<TimeFunction>, 3>& a,
                            const std::array<std::optional<TimeFunction>, 3>& b,
                            const std::string& what) {
  for (std::size_t axis = 0; axis < 3; ++axis) {
    ASSERT_EQ(a[axis].has_value(), b[axis].has_value()) << what << " axis " << axis;
    if (a[axis]) expect_same_function(*a[axis], *b[axis], what);
  }
}

/// Every field except locations (which differ between a file and its rewrite).
void expect_same_case(const CaseDescription& a, const CaseDescription& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(a.model, b.model);
  EXPECT_EQ(a.dimension, b.dimension);
  EXPECT_EQ(a.plane, b.plane);
  EXPECT_EQ(a.geometry.spacing, b.geometry.spacing);
  EXPECT_EQ(a.geometry.cells, b.geometry.cells);
  ASSERT_EQ(a.geometry.shapes.size(), b.geometry.shapes.size());
  for (std::size_t i = 0; i < a.geometry.shapes.size(); ++i) {
    EXPECT_EQ(a.geometry.shapes[i].kind, b.geometry.shapes[i].kind);
    EXPECT_EQ(a.geometry.shapes[i].vertices, b.geometry.shapes[i].vertices);
    EXPECT_EQ(a.geometry.shapes[i].material, b.geometry.shapes[i].material);
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (const auto& [name, block] : a.materials) {
    const ParameterBlock& other = b.materials.at(name);
    EXPECT_EQ(block.path, other.path);
    ASSERT_EQ(block.values.size(), other.values.size()) << name;
    for (const auto& [key, parameter] : block.values) {
      EXPECT_EQ(parameter.value, other.values.at(key).value) << name << "." << key;
    }
    ASSERT_EQ(block.words.size(), other.words.size());
    for (const auto& [key, word] : block.words)
      EXPECT_EQ(word.first, other.words.at(key).first);
  }
  ASSERT_EQ(a.groups.size(), b.groups.size());
  for (std::size_t i = 0; i < a.groups.size(); ++i) {
    EXPECT_EQ(a.groups[i].name, b.groups[i].name);
    EXPECT_EQ(a.groups[i].kind, b.groups[i].kind);
    EXPECT_EQ(a.groups[i].edge, b.groups[i].edge);
    EXPECT_EQ(a.groups[i].min, b.groups[i].min);
    EXPECT_EQ(a.groups[i].max, b.groups[i].max);
    EXPECT_EQ(a.groups[i].vertices, b.groups[i].vertices);
    EXPECT_EQ(a.groups[i].point, b.groups[i].point);
  }
  ASSERT_EQ(a.boundary_conditions.size(), b.boundary_conditions.size());
  for (std::size_t i = 0; i < a.boundary_conditions.size(); ++i) {
    const BoundaryConditionSpec& x = a.boundary_conditions[i];
    const BoundaryConditionSpec& y = b.boundary_conditions[i];
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.group, y.group);
    expect_same_components(x.velocity, y.velocity, "velocity " + std::to_string(i));
    expect_same_components(x.traction, y.traction, "traction " + std::to_string(i));
    EXPECT_EQ(x.axis, y.axis);
    EXPECT_EQ(x.mirror, y.mirror);
  }
  ASSERT_EQ(a.gravity.has_value(), b.gravity.has_value());
  if (a.gravity) {
    EXPECT_EQ(a.gravity->acceleration, b.gravity->acceleration);
    expect_same_function(a.gravity->factor, b.gravity->factor, "gravity factor");
  }
  ASSERT_EQ(a.damping.has_value(), b.damping.has_value());
  if (a.damping) {
    EXPECT_EQ(a.damping->coefficient, b.damping->coefficient);
    EXPECT_EQ(a.damping->start, b.damping->start);
    EXPECT_EQ(a.damping->end, b.damping->end);
  }
  EXPECT_EQ(a.initial.velocity, b.initial.velocity);
  EXPECT_EQ(a.initial.geostatic_surface, b.initial.geostatic_surface);
  EXPECT_EQ(a.initial.k0, b.initial.k0);
  const NumericsSpec& n = a.numerics;
  const NumericsSpec& m = b.numerics;
  EXPECT_EQ(n.kernel, m.kernel);
  EXPECT_EQ(n.h_over_dx, m.h_over_dx);
  EXPECT_EQ(n.interpolation_order, m.interpolation_order);
  EXPECT_EQ(n.courant, m.courant);
  EXPECT_EQ(n.time_step, m.time_step);
  EXPECT_EQ(n.frozen_flux_source, m.frozen_flux_source);
  EXPECT_EQ(n.rk_substep_factor, m.rk_substep_factor);
  EXPECT_EQ(n.rk_max_substeps, m.rk_max_substeps);
  EXPECT_EQ(n.hourglass_filter, m.hourglass_filter);
  EXPECT_EQ(n.hourglass_kappa, m.hourglass_kappa);
  EXPECT_EQ(n.hourglass_h_over_dx, m.hourglass_h_over_dx);
  // The resolved case writes the computed defaults: an unset value reads back as that default.
  EXPECT_EQ(n.hourglass_fields.value_or(default_hourglass_fields(n, a.dimension)),
            m.hourglass_fields.value_or(default_hourglass_fields(m, b.dimension)));
  EXPECT_EQ(n.stress_update.value_or(default_stress_update(a.dimension)),
            m.stress_update.value_or(default_stress_update(b.dimension)));
  EXPECT_EQ(n.artificial_viscosity, m.artificial_viscosity);
  EXPECT_EQ(a.time.end, b.time.end);
  EXPECT_EQ(a.time.max_steps, b.time.max_steps);
  EXPECT_EQ(a.output.interval, b.output.interval);
  EXPECT_EQ(a.output.probe_interval, b.output.probe_interval);
  EXPECT_EQ(a.output.fields, b.output.fields);
  ASSERT_EQ(a.probes.size(), b.probes.size());
  for (std::size_t i = 0; i < a.probes.size(); ++i) {
    EXPECT_EQ(a.probes[i].name, b.probes[i].name);
    EXPECT_EQ(a.probes[i].group, b.probes[i].group);
    EXPECT_EQ(a.probes[i].fields, b.probes[i].fields);
    EXPECT_EQ(a.probes[i].reduction, b.probes[i].reduction);
  }
}

TEST(CaseWriter, RoundTripOfTheRichCase) {
  const CaseDescription original = read_case_file(fixture_path("rich2d.yaml"));
  const std::string written = write_case_yaml(original);
  const CaseDescription reread = read_case_text(written, "written.yaml");
  expect_same_case(original, reread);
  // Writing is a fixed point after one pass.
  EXPECT_EQ(write_case_yaml(reread), written);
}

TEST(CaseWriter, RoundTripKeepsDefaultsAndAwkwardValues) {
  const std::string text =
      replace_once(read_fixture("bar1d_minimal.yaml"), "name: bar1d-minimal",
                   "name: bar1d-minimal\ndescription: 'quotes \" and: colons, # hashes'") +
      "loads:\n  damping: {coefficient: 0.1}\n  gravity: {acceleration: -9.81}\n"
      "initial_conditions: {geostatic: {surface: 10.0}}\n"
      "numerics: {time_step: 3.3333333333333335e-05}\n";
  const CaseDescription original = read_case_text(text, kFile);
  EXPECT_EQ(original.damping->end, 1e300);  // "forever" by default
  const std::string written = write_case_yaml(original);
  const CaseDescription reread = read_case_text(written, "written.yaml");
  expect_same_case(original, reread);
  EXPECT_EQ(reread.description, "quotes \" and: colons, # hashes");
  EXPECT_EQ(*reread.numerics.time_step, 3.3333333333333335e-05);  // every digit kept
}

TEST(CaseReader, EmptyTextIsAnInputError) {
  const InputError error = read_error("# nothing but a comment\n");
  EXPECT_EQ(error.location().file, kFile);
  EXPECT_NE(error.problem().find("empty"), std::string::npos);
}

TEST(CaseReader, MissingFileIsAnInputError) {
  try {
    read_case_file(fixture_path("no-such-case.yaml"));
    ADD_FAILURE() << "expected an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.location().file, fixture_path("no-such-case.yaml"));
  }
}

// ------------------------------------------------------------------------------------------------
// pore_fluid.water_table (docs/input-reference.md, "water_table"; docs/theory.md §6.8)

namespace water_table {

const std::string kEntry = "  solver_tolerance: 1.0e-9\n";

std::string with_table(const std::string& table) {
  return replace_once(read_fixture("rich2d.yaml"), kEntry,
                      kEntry + "  water_table: " + table + "\n");
}

}  // namespace water_table

TEST(CaseReader, WaterTableLevelPolylineAndDensityAboveAreRead) {
  EXPECT_FALSE(read_case_text(read_fixture("rich2d.yaml"), kFile).pore_fluid->water_table);
  const CaseDescription level = read_case_text(water_table::with_table("{level: 4.5}"), kFile);
  ASSERT_TRUE(level.pore_fluid->water_table);
  EXPECT_EQ(level.pore_fluid->water_table->level, 4.5);
  EXPECT_TRUE(level.pore_fluid->water_table->polyline.empty());
  EXPECT_FALSE(level.pore_fluid->water_table->density_above);
  const CaseDescription polyline = read_case_text(
      water_table::with_table("{polyline: [[0, 8], [20, 8], [40, 2]], density_above: 1800}"),
      kFile);
  const WaterTableSpec& table = *polyline.pore_fluid->water_table;
  EXPECT_FALSE(table.level);
  ASSERT_EQ(table.polyline.size(), 3u);
  EXPECT_EQ(table.polyline[2][0], 40.0);
  EXPECT_EQ(table.polyline[2][1], 2.0);
  EXPECT_EQ(table.density_above, 1800.0);
}

TEST(CaseReader, WaterTableWithBothOrNeitherShapeIsRejected) {
  const std::string both = water_table::with_table("{level: 4.5, polyline: [[0, 1], [2, 3]]}");
  const InputError two = read_error(both);
  EXPECT_EQ(two.location().file, kFile);
  EXPECT_EQ(two.location().line, position_of(both, "water_table:").line);
  EXPECT_EQ(two.key(), "pore_fluid.water_table.polyline");
  EXPECT_NE(two.allowed().find("exactly one of level"), std::string::npos) << two.what();
  const std::string neither = water_table::with_table("{density_above: 1800}");
  const InputError none = read_error(neither);
  EXPECT_EQ(none.key(), "pore_fluid.water_table");
  EXPECT_EQ(none.location().line, position_of(neither, "water_table:").line);
  EXPECT_NE(none.allowed().find("exactly one of level"), std::string::npos) << none.what();
}

TEST(CaseReader, WaterTablePolylineMustRiseInXAndHaveTwoVertices) {
  const std::string text = water_table::with_table("{polyline: [[0, 8], [20, 8], [15, 2]]}");
  const InputError error = read_error(text);
  EXPECT_EQ(error.location().file, kFile);
  EXPECT_EQ(error.location().line, position_of(text, "water_table:").line);
  EXPECT_EQ(error.key(), "pore_fluid.water_table.polyline.2");
  EXPECT_EQ(error.value(), "[15, 2]");
  EXPECT_NE(error.allowed().find("x strictly increasing"), std::string::npos) << error.what();
  EXPECT_NE(error.problem().find("x = 15"), std::string::npos) << error.what();
  const InputError single = read_error(water_table::with_table("{polyline: [[0, 8]]}"));
  EXPECT_EQ(single.key(), "pore_fluid.water_table.polyline");
  const InputError bad_density =
      read_error(water_table::with_table("{level: 3, density_above: -1}"));
  EXPECT_EQ(bad_density.key(), "pore_fluid.water_table.density_above");
  EXPECT_EQ(bad_density.value(), "-1");
  EXPECT_NE(bad_density.allowed().find("> 0"), std::string::npos) << bad_density.what();
  const InputError unknown = read_error(water_table::with_table("{levl: 3}"));
  EXPECT_EQ(unknown.key(), "pore_fluid.water_table.levl");
  EXPECT_NE(std::string(unknown.what()).find("level"), std::string::npos) << unknown.what();
}

}  // namespace
}  // namespace rktsph::case_reader_test
