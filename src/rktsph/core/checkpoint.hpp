// Checkpoints: the whole state of a run in one binary file, so that a killed run continues
// (`rktsph run CASE --restart RUN_DIR`) to results bit-identical to an uninterrupted run
// (docs/input-reference.md, "Checkpoint and restart").
//
// Layout (every integer and double little-endian, doubles as their IEEE 754 bits):
//   "RKTSPHCK"                 8 bytes, the magic
//   u32 format version         kCheckpointFormatVersion
//   u64 case hash              FNV-1a 64 of the resolved case text (write_case_yaml)
//   string rktsph version      u32 length, then the bytes
//   u32 section count, then per section: string name, u64 length, the bytes
//   u64 checksum               FNV-1a 64 of every byte before it
// Each stateful part of a run (the simulation, each output observer, the checkpoint writer
// itself) saves into its own named section and reads back only what it saved.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "rktsph/core/field_array.hpp"

namespace rktsph {

/// Bumped whenever the layout or the content of a section changes; a build reads only its own
/// version, since a section from another version cannot be trusted to mean the same thing.
inline constexpr std::uint32_t kCheckpointFormatVersion =
    8;  // 2: hourglass forces; 3: configuration; 4: energy budget; 5: filter configuration;
        // 6: cells formed again; 7: rigid bodies' force sums; 8: loaded bodies' motion
inline constexpr const char* kCheckpointFileName = "checkpoint.bin";

/// FNV-1a, 64 bits: the case hash and the file checksum (no dependency beyond the standard
/// library; it detects a changed case or a damaged file, it is not meant to resist tampering).
std::uint64_t fnv1a_64(std::string_view bytes);

/// Appends little-endian values to a byte string.
class CheckpointOut {
 public:
  void put_u32(std::uint32_t value);
  void put_u64(std::uint64_t value);
  void put_i64(std::int64_t value) { put_u64(static_cast<std::uint64_t>(value)); }
  void put_f64(double value);
  void put_string(std::string_view text);
  /// The bytes as they are, with no length before them.
  void put_raw(std::string_view bytes) { bytes_.append(bytes); }
  void put_doubles(const double* values, std::size_t count);
  void put_doubles(const std::vector<double>& values) { put_doubles(values.data(), values.size()); }
  /// Field count, point count, then the values.
  void put_fields(const FieldArray& fields);

  const std::string& bytes() const { return bytes_; }

 private:
  std::string bytes_;
};

/// Reads back what CheckpointOut wrote. Reading past the end, or a count or shape that does not
/// match, throws the InputError of a damaged checkpoint naming `file`.
class CheckpointIn {
 public:
  CheckpointIn(std::string_view bytes, std::filesystem::path file, std::string section);

  std::uint32_t get_u32();
  std::uint64_t get_u64();
  std::int64_t get_i64() { return static_cast<std::int64_t>(get_u64()); }
  double get_f64();
  std::string get_string();
  std::vector<double> get_doubles();
  /// `count` doubles into `values`; the stored count must be `count`.
  void get_doubles_into(double* values, std::size_t count);
  /// Values into `fields`, whose field and point counts the stored ones must equal.
  void get_fields_into(FieldArray& fields);
  /// The next `count` bytes as they are.
  std::string_view get_raw(std::size_t count);
  /// Every byte of the section must have been read.
  void expect_end() const;
  /// The InputError of a damaged checkpoint, `detail` saying what did not fit.
  [[noreturn]] void fail(const std::string& detail) const;

 private:
  std::string_view bytes_;
  std::size_t position_ = 0;
  std::filesystem::path file_;
  std::string section_;
};

/// A part of a run whose state a checkpoint keeps.
class Checkpointed {
 public:
  virtual ~Checkpointed() = default;
  virtual void save_checkpoint(CheckpointOut& out) const = 0;
  /// Reads exactly what save_checkpoint wrote; throws through `in` if it does not fit.
  virtual void restore_checkpoint(CheckpointIn& in) = 0;
};

/// One part and the name of its section.
struct CheckpointPart {
  std::string section;
  Checkpointed* part;
};

/// A decoded checkpoint file.
struct CheckpointFile {
  std::filesystem::path path;
  std::uint64_t case_hash = 0;
  std::string rktsph_version;
  std::map<std::string, std::string> sections;
};

/// The file content for these parts (each part's section in the order given).
std::string encode_checkpoint(std::uint64_t case_hash, const std::vector<CheckpointPart>& parts);

/// Decodes `bytes` (the content of `path`), refusing with an InputError (exit status 2) that
/// names the path: a file that is not a checkpoint, another format version, a truncated or
/// damaged file, or one written for another case (hash other than `expected_case_hash`).
CheckpointFile decode_checkpoint(const std::string& bytes, const std::filesystem::path& path,
                                 std::uint64_t expected_case_hash);

/// Reads and decodes `run_directory`/checkpoint.bin; also an InputError if it does not exist.
CheckpointFile read_checkpoint(const std::filesystem::path& run_directory,
                               std::uint64_t expected_case_hash);

/// Restores every part from its section; a missing section, or one not read to its end, is a
/// damaged checkpoint.
void restore_checkpoint_parts(const CheckpointFile& file, const std::vector<CheckpointPart>& parts);

}  // namespace rktsph
