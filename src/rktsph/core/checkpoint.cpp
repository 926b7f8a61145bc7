#include "rktsph/core/checkpoint.hpp"

#include <fmt/format.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include "rktsph/core/error.hpp"

namespace rktsph {

namespace {

constexpr std::string_view kMagic = "RKTSPHCK";
constexpr std::size_t kChecksumBytes = 8;

const char* const kRunAgain = "or run the case again without --restart";

[[noreturn]] void refuse(const std::filesystem::path& path, const std::string& problem,
                         const std::string& allowed) {
  throw InputError(SourceLocation{path.string(), 0, 0}, "--restart", "", problem, allowed);
}

[[noreturn]] void refuse_damaged(const std::filesystem::path& path, const std::string& detail) {
  refuse(path, fmt::format("the checkpoint is truncated or damaged ({})", detail),
         fmt::format("a complete checkpoint written by this build, {}", kRunAgain));
}

std::uint64_t read_u64_at(std::string_view bytes, std::size_t offset) {
  std::uint64_t value = 0;
  for (int b = 7; b >= 0; --b)
    value = (value << 8) | static_cast<unsigned char>(bytes[offset + static_cast<std::size_t>(b)]);
  return value;
}

}  // namespace

std::uint64_t fnv1a_64(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (const char c : bytes) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  return hash;
}

void CheckpointOut::put_u32(std::uint32_t value) {
  for (int b = 0; b < 4; ++b)
    bytes_.push_back(static_cast<char>((value >> (8 * b)) & 0xffu));
}

void CheckpointOut::put_u64(std::uint64_t value) {
  for (int b = 0; b < 8; ++b)
    bytes_.push_back(static_cast<char>((value >> (8 * b)) & 0xffu));
}

void CheckpointOut::put_f64(double value) {
  std::uint64_t bits = 0;
  static_assert(sizeof bits == sizeof value);
  std::memcpy(&bits, &value, sizeof bits);
  put_u64(bits);
}

void CheckpointOut::put_string(std::string_view text) {
  put_u32(static_cast<std::uint32_t>(text.size()));
  bytes_.append(text);
}

void CheckpointOut::put_doubles(const double* values, std::size_t count) {
  put_u64(count);
  for (std::size_t i = 0; i < count; ++i)
    put_f64(values[i]);
}

void CheckpointOut::put_fields(const FieldArray& fields) {
  put_u32(static_cast<std::uint32_t>(fields.field_count()));
  put_u64(fields.point_count());
  put_doubles(fields.data());
}

CheckpointIn::CheckpointIn(std::string_view bytes, std::filesystem::path file, std::string section)
    : bytes_(bytes), file_(std::move(file)), section_(std::move(section)) {}

void CheckpointIn::fail(const std::string& detail) const {
  refuse_damaged(file_, fmt::format("section '{}': {}", section_, detail));
}

std::string_view CheckpointIn::get_raw(std::size_t count) {
  if (count > bytes_.size() - position_)
    fail(fmt::format("needs {} more bytes at offset {} of {}", count, position_, bytes_.size()));
  const std::string_view taken = bytes_.substr(position_, count);
  position_ += count;
  return taken;
}

std::uint32_t CheckpointIn::get_u32() {
  const std::string_view b = get_raw(4);
  std::uint32_t value = 0;
  for (int i = 3; i >= 0; --i)
    value = (value << 8) | static_cast<unsigned char>(b[static_cast<std::size_t>(i)]);
  return value;
}

std::uint64_t CheckpointIn::get_u64() {
  return read_u64_at(get_raw(8), 0);
}

double CheckpointIn::get_f64() {
  const std::uint64_t bits = get_u64();
  double value = 0.0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

std::string CheckpointIn::get_string() {
  const std::uint32_t length = get_u32();
  return std::string(get_raw(length));
}

std::vector<double> CheckpointIn::get_doubles() {
  const std::uint64_t count = get_u64();
  // Checked before allocating, so a damaged count cannot ask for more memory than the file holds.
  if (count > (bytes_.size() - position_) / 8)
    fail(fmt::format("{} values announced, {} bytes left", count, bytes_.size() - position_));
  std::vector<double> values(count);
  for (double& value : values)
    value = get_f64();
  return values;
}

void CheckpointIn::get_doubles_into(double* values, std::size_t count) {
  const std::uint64_t stored = get_u64();
  if (stored != count) fail(fmt::format("{} values stored where this case has {}", stored, count));
  for (std::size_t i = 0; i < count; ++i)
    values[i] = get_f64();
}

void CheckpointIn::get_fields_into(FieldArray& fields) {
  const std::uint32_t field_count = get_u32();
  const std::uint64_t point_count = get_u64();
  if (field_count != static_cast<std::uint32_t>(fields.field_count()) ||
      point_count != fields.point_count())
    fail(fmt::format("{} fields on {} points stored where this case has {} on {}", field_count,
                     point_count, fields.field_count(), fields.point_count()));
  get_doubles_into(fields.data().data(), fields.data().size());
}

void CheckpointIn::expect_end() const {
  if (position_ != bytes_.size())
    fail(fmt::format("{} bytes left unread", bytes_.size() - position_));
}

std::string encode_checkpoint(std::uint64_t case_hash, const std::vector<CheckpointPart>& parts) {
  CheckpointOut out;
  out.put_raw(kMagic);
  out.put_u32(kCheckpointFormatVersion);
  out.put_u64(case_hash);
  out.put_string(RKTSPH_VERSION);
  out.put_u32(static_cast<std::uint32_t>(parts.size()));
  for (const CheckpointPart& part : parts) {
    CheckpointOut section;
    part.part->save_checkpoint(section);
    out.put_string(part.section);
    out.put_u64(section.bytes().size());
    out.put_raw(section.bytes());
  }
  out.put_u64(fnv1a_64(out.bytes()));
  return out.bytes();
}

CheckpointFile decode_checkpoint(const std::string& bytes, const std::filesystem::path& path,
                                 std::uint64_t expected_case_hash) {
  const std::string_view all(bytes);
  if (all.size() < kMagic.size() || all.substr(0, kMagic.size()) != kMagic)
    refuse(
        path, "not an rktsph checkpoint (it does not start with \"RKTSPHCK\")",
        fmt::format("the checkpoint.bin of a run with output.checkpoint_interval, {}", kRunAgain));
  if (all.size() < kMagic.size() + 4 + kChecksumBytes)
    refuse_damaged(path, fmt::format("only {} bytes", all.size()));
  // The version is read before anything else is trusted: another version may lay out the rest
  // differently, and "wrong format version" says more than a checksum failure would.
  CheckpointIn version_reader(all.substr(kMagic.size(), 4), path, "header");
  const std::uint32_t version = version_reader.get_u32();
  if (version != kCheckpointFormatVersion)
    refuse(path,
           fmt::format("checkpoint format version {}, but this build of rktsph reads only "
                       "version {}",
                       version, kCheckpointFormatVersion),
           fmt::format("a checkpoint written by an rktsph with format version {}, {}",
                       kCheckpointFormatVersion, kRunAgain));
  const std::string_view body = all.substr(0, all.size() - kChecksumBytes);
  const std::uint64_t stored_checksum = read_u64_at(all, body.size());
  if (fnv1a_64(body) != stored_checksum)
    refuse_damaged(path, fmt::format("checksum mismatch over its {} bytes, e.g. a run killed "
                                     "while it was copied, or a truncated copy",
                                     all.size()));

  CheckpointIn in(body.substr(kMagic.size() + 4), path, "header");
  CheckpointFile file;
  file.path = path;
  file.case_hash = in.get_u64();
  file.rktsph_version = in.get_string();
  if (file.case_hash != expected_case_hash)
    refuse(path,
           fmt::format("the checkpoint was written for a different case: case hash {:016x} in "
                       "the checkpoint, {:016x} for this case file with these --set overrides",
                       file.case_hash, expected_case_hash),
           "the case file and the same --set overrides as the run that wrote it (its resolved "
           "case is case.yaml in the run folder)");
  const std::uint32_t count = in.get_u32();
  for (std::uint32_t s = 0; s < count; ++s) {
    std::string name = in.get_string();
    const std::uint64_t length = in.get_u64();
    std::string content(in.get_raw(length));
    if (!file.sections.emplace(std::move(name), std::move(content)).second)
      in.fail("a section is listed twice");
  }
  in.expect_end();
  return file;
}

CheckpointFile read_checkpoint(const std::filesystem::path& run_directory,
                               std::uint64_t expected_case_hash) {
  const std::filesystem::path path = run_directory / kCheckpointFileName;
  std::error_code error;
  if (!std::filesystem::is_directory(run_directory, error))
    refuse(run_directory, "no such run folder",
           "the output folder of a run started with output.checkpoint_interval > 0");
  if (!std::filesystem::is_regular_file(path, error))
    refuse(path,
           "no checkpoint in the run folder (a run writes one only with "
           "output.checkpoint_interval > 0, first at that simulated time)",
           fmt::format("the output folder of a run that wrote a checkpoint, {}", kRunAgain));
  std::ifstream stream(path, std::ios::binary);
  std::ostringstream content;
  content << stream.rdbuf();
  if (!stream) refuse(path, "cannot read the checkpoint", "a readable checkpoint.bin");
  return decode_checkpoint(content.str(), path, expected_case_hash);
}

void restore_checkpoint_parts(const CheckpointFile& file,
                              const std::vector<CheckpointPart>& parts) {
  for (const CheckpointPart& part : parts) {
    const auto section = file.sections.find(part.section);
    if (section == file.sections.end())
      refuse_damaged(file.path, fmt::format("no section '{}'", part.section));
    CheckpointIn in(section->second, file.path, part.section);
    part.part->restore_checkpoint(in);
    in.expect_end();
  }
}

}  // namespace rktsph
