// The checkpoint file (src/rktsph/core/checkpoint.hpp): values come back bit for bit, a
// damaged file is refused rather than read, and a simulation restored from a checkpoint takes
// the same next steps as the one that wrote it (also the saturated model, whose pressure solve
// starts from the previous steps' p_w).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/simulation/simulation.hpp"

namespace rktsph::checkpoint_test {
namespace {

std::uint64_t bits_of(double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

// A part holding arbitrary values, to check the encoding itself.
struct Values final : Checkpointed {
  std::vector<double> numbers;
  std::string text;
  std::uint64_t count = 0;
  void save_checkpoint(CheckpointOut& out) const override {
    out.put_doubles(numbers);
    out.put_string(text);
    out.put_u64(count);
  }
  void restore_checkpoint(CheckpointIn& in) override {
    numbers = in.get_doubles();
    text = in.get_string();
    count = in.get_u64();
  }
};

TEST(CheckpointFormat, DoublesStringsAndCountsComeBackBitForBit) {
  Values saved;
  double quiet_nan = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t payload = bits_of(quiet_nan) | 0x1234u;
  std::memcpy(&quiet_nan, &payload, sizeof quiet_nan);
  saved.numbers = {0.1,
                   -0.0,
                   std::numeric_limits<double>::denorm_min(),
                   std::numeric_limits<double>::max(),
                   -std::numeric_limits<double>::infinity(),
                   quiet_nan,
                   1.0 / 3.0};
  saved.text = "probes";
  saved.count = 0xfedcba9876543210ull;
  const std::string bytes = encode_checkpoint(42, {{"values", &saved}});
  EXPECT_EQ(bytes.substr(0, 8), "RKTSPHCK");

  const CheckpointFile file = decode_checkpoint(bytes, "test.bin", 42);
  EXPECT_EQ(file.rktsph_version, RKTSPH_VERSION);
  Values restored;
  restore_checkpoint_parts(file, {{"values", &restored}});
  ASSERT_EQ(restored.numbers.size(), saved.numbers.size());
  for (std::size_t i = 0; i < saved.numbers.size(); ++i)
    EXPECT_EQ(bits_of(restored.numbers[i]), bits_of(saved.numbers[i])) << i;
  EXPECT_EQ(restored.text, saved.text);
  EXPECT_EQ(restored.count, saved.count);
}

TEST(CheckpointFormat, CaseHashIsFnv1a64) {
  EXPECT_EQ(fnv1a_64(""), 0xcbf29ce484222325ull);  // the published test vectors
  EXPECT_EQ(fnv1a_64("a"), 0xaf63dc4c8601ec8cull);
  EXPECT_EQ(fnv1a_64("foobar"), 0x85944171f73967e8ull);
}

std::string refusal(const std::string& bytes, std::uint64_t hash,
                    const std::vector<CheckpointPart>& parts = {}) {
  try {
    restore_checkpoint_parts(decode_checkpoint(bytes, "run/checkpoint.bin", hash), parts);
  } catch (const InputError& error) {
    return error.what();
  }
  return "accepted";
}

TEST(CheckpointFormat, EveryTruncationIsRefused) {
  Values saved;
  saved.numbers = {1.0, 2.0};
  const std::string bytes = encode_checkpoint(7, {{"values", &saved}});
  for (std::size_t length = 0; length < bytes.size(); ++length) {
    const std::string message = refusal(bytes.substr(0, length), 7);
    EXPECT_EQ(message.rfind("run/checkpoint.bin: error: key '--restart': ", 0), 0u)
        << length << ": " << message;
  }
}

TEST(CheckpointFormat, MissingSectionOrUnreadBytesAreRefused) {
  Values saved;
  const std::string bytes = encode_checkpoint(7, {{"values", &saved}});
  Values other;
  EXPECT_NE(refusal(bytes, 7, {{"other", &other}}).find("no section 'other'"), std::string::npos);

  struct Shorter final : Checkpointed {  // reads less than Values wrote
    void save_checkpoint(CheckpointOut&) const override {}
    void restore_checkpoint(CheckpointIn& in) override { in.get_doubles(); }
  } shorter;
  EXPECT_NE(refusal(bytes, 7, {{"values", &shorter}}).find("bytes left unread"), std::string::npos);
}

TEST(CheckpointFormat, AnnouncedCountBeyondTheDataIsRefusedBeforeAllocating) {
  CheckpointOut out;
  out.put_u64(std::uint64_t{1} << 60);  // 2^60 doubles announced, none there
  CheckpointIn in(out.bytes(), "run/checkpoint.bin", "values");
  EXPECT_THROW(in.get_doubles(), InputError);
}

CaseDescription saturated_column() {
  return read_case_file(
      std::string(RKTSPH_TEST_DATA_DIR) + "/../../cases/vpw-consolidation/case.yaml",
      {{"time.end", "1.0"}});
}

CaseDescription softening_sample_with_strain_stiffness() {
  return read_case_file(
      std::string(RKTSPH_TEST_DATA_DIR) + "/../../cases/sample2d-localization/case.yaml",
      {{"geometry.spacing", "0.05"},
       {"time.end", "0.05"},
       {"numerics.hourglass.strain_stiffness", "0.2"},
       {"numerics.hourglass.stiffness", "0.5"}});
}

void advance(Simulation& simulation, int steps) {
  for (int s = 0; s < steps; ++s)
    simulation.step().advance(simulation.state(), simulation.time_step());
}

void expect_identical(const FieldArray& a, const FieldArray& b) {
  ASSERT_EQ(a.data().size(), b.data().size());
  std::size_t different = 0;
  for (std::size_t i = 0; i < a.data().size(); ++i)
    different += bits_of(a.data()[i]) != bits_of(b.data()[i]);
  EXPECT_EQ(different, 0u);
}

// Simulation `original` takes 40 steps and writes a checkpoint; a fresh simulation restored from
// it and the original then take 40 more steps each and must agree bit for bit.
void expect_restored_simulation_continues_identically(const CaseDescription& description) {
  Simulation original(description);
  advance(original, 40);
  const std::string bytes = encode_checkpoint(1, {{"simulation", &original}});

  Simulation restored(description);
  restore_checkpoint_parts(decode_checkpoint(bytes, "memory", 1), {{"simulation", &restored}});
  EXPECT_EQ(restored.state().step, 40);
  advance(original, 40);
  advance(restored, 40);
  EXPECT_EQ(bits_of(restored.state().time), bits_of(original.state().time));
  expect_identical(restored.state().fields, original.state().fields);
  expect_identical(restored.state().internal, original.state().internal);
  expect_identical(restored.state().displacement, original.state().displacement);
  expect_identical(restored.state().strain, original.state().strain);
  EXPECT_EQ(restored.step().neighbour_searches(), original.step().neighbour_searches());
}

TEST(CheckpointSimulation, RestoredSaturatedRunTakesTheSameSteps) {
  const CaseDescription description = saturated_column();
  expect_restored_simulation_continues_identically(description);
  // The pressure solve's statistics continue too (summary.json of a restarted run).
  Simulation original(description);
  advance(original, 10);
  const std::string bytes = encode_checkpoint(1, {{"simulation", &original}});
  Simulation restored(description);
  restore_checkpoint_parts(decode_checkpoint(bytes, "memory", 1), {{"simulation", &restored}});
  EXPECT_EQ(restored.pressure_projection()->statistics().solves, 10);
}

TEST(CheckpointSimulation, RestoredSofteningRunWithStrainStiffnessTakesTheSameSteps) {
  const CaseDescription description = softening_sample_with_strain_stiffness();
  ASSERT_GT(Simulation(description).state().strain.field_count(), 0);
  expect_restored_simulation_continues_identically(description);
}

// The collapsing block of ld-slope-low-cohesion on a coarse lattice, with the stencils searched and
// the filter rebuilt after a few steps' motion instead of every step (docs/theory.md §9.5).
CaseDescription collapsing_block() {
  return read_case_file(
      std::string(RKTSPH_TEST_DATA_DIR) + "/../../cases/ld-slope-low-cohesion/case.yaml",
      {{"geometry.spacing", "2.0"},
       {"time.end", "1.0"},
       {"numerics.neighbour_search_distance", "0.2"}});
}

TEST(CheckpointSimulation, RestoredLargeDeformationRunSearchesItsStencilsWhereTheRunDid) {
  const CaseDescription description = collapsing_block();
  // The checkpoint must fall between two searches, and searches must follow it, or the restart
  // would not have to search again from an older configuration.
  Simulation probe(description);
  advance(probe, 40);
  const long searches_at_checkpoint = probe.step().neighbour_searches();
  advance(probe, 1);
  ASSERT_EQ(probe.step().neighbour_searches(), searches_at_checkpoint)
      << "the step after the checkpoint must use the stencils of an earlier search";
  advance(probe, 39);
  const long searches_after = probe.step().neighbour_searches() - searches_at_checkpoint;
  ASSERT_GT(searches_after, 1);
  ASSERT_LT(searches_after, 40);
  expect_restored_simulation_continues_identically(description);
}

}  // namespace
}  // namespace rktsph::checkpoint_test
