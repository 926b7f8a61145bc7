#include "rktsph/output/output_folder.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <string_view>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"
#include "rktsph/output/atomic_file.hpp"

namespace rktsph {

namespace fs = std::filesystem;

namespace {

// The files a run writes at the top of its folder; the field files are matched by pattern.
constexpr std::array<const char*, 6> kResultFileNames = {
    "summary.json", "case.yaml", "series.pvd", "probes.csv", "run.log", "checkpoint.bin"};

[[noreturn]] void unusable_folder(const fs::path& directory, const std::string& action,
                                  int error_number) {
  throw InputError({}, "", "",
                   fmt::format("cannot {} the output folder '{}': {}", action, directory.string(),
                               describe_system_error(error_number)),
                   "");
}

// "fields_000012.vtu", as FieldSeriesWriter names them.
bool is_field_file_name(std::string_view name) {
  constexpr std::string_view prefix = "fields_", suffix = ".vtu";
  if (name.size() <= prefix.size() + suffix.size()) return false;
  if (!name.starts_with(prefix) || !name.ends_with(suffix)) return false;
  for (const char c : name.substr(prefix.size(), name.size() - prefix.size() - suffix.size()))
    if (c < '0' || c > '9') return false;
  return true;
}

// A real directory, not a symlink to one: nothing is removed through a link.
bool is_real_directory(const fs::path& path) {
  std::error_code error;
  return fs::symlink_status(path, error).type() == fs::file_type::directory;
}

bool exists_without_following(const fs::path& path) {
  std::error_code error;
  return fs::symlink_status(path, error).type() != fs::file_type::not_found && !error;
}

// The PID the holder wrote into the lock file, or 0 if there is none (yet).
long lock_holder(int descriptor) {
  std::array<char, 32> text{};
  const ssize_t count = ::pread(descriptor, text.data(), text.size() - 1, 0);
  if (count <= 0) return 0;
  long pid = 0;
  for (ssize_t i = 0; i < count && text[static_cast<std::size_t>(i)] >= '0' &&
                      text[static_cast<std::size_t>(i)] <= '9';
       ++i)
    pid = pid * 10 + (text[static_cast<std::size_t>(i)] - '0');
  return pid;
}

void record_holder(int descriptor) {
  const std::string pid = fmt::format("{}\n", static_cast<long>(::getpid()));
  // Only informative (for the message of a run that finds the folder busy): failures are harmless.
  if (::ftruncate(descriptor, 0) == 0) {
    [[maybe_unused]] const ssize_t written = ::pwrite(descriptor, pid.data(), pid.size(), 0);
  }
}

std::string describe_results(const std::vector<fs::path>& files) {
  std::string names;
  std::size_t field_files = 0;
  for (const fs::path& file : files) {
    if (file.parent_path().filename() == "fields") {
      ++field_files;
      continue;
    }
    names += (names.empty() ? "" : ", ") + file.filename().string();
  }
  if (field_files > 0)
    names += fmt::format("{}{} field file{} in fields/", names.empty() ? "" : ", ", field_files,
                         field_files == 1 ? "" : "s");
  return names;
}

}  // namespace

std::vector<fs::path> run_result_files(const fs::path& directory) {
  std::vector<fs::path> files;
  for (const char* name : kResultFileNames)
    if (exists_without_following(directory / name)) files.push_back(directory / name);
  const fs::path fields = directory / "fields";
  if (is_real_directory(fields)) {
    std::vector<fs::path> field_files;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(fields, error))
      if (is_field_file_name(entry.path().filename().string())) field_files.push_back(entry.path());
    std::sort(field_files.begin(), field_files.end());
    files.insert(files.end(), field_files.begin(), field_files.end());
  }
  return files;
}

OutputFolder::OutputFolder(fs::path directory, ExistingResults existing)
    : directory_(std::move(directory)) {
  if (directory_.empty())
    throw InputError({}, "-o", "", "the output folder name is empty", "a folder name");
  std::error_code error;
  fs::create_directories(directory_, error);
  if (error) unusable_folder(directory_, "create", error.value());
  if (!fs::is_directory(directory_)) unusable_folder(directory_, "use", ENOTDIR);

  const fs::path lock_path = directory_ / kOutputLockName;
  lock_descriptor_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0666);
  if (lock_descriptor_ < 0) unusable_folder(directory_, "write to", errno);
  // Non-blocking: a second run into a busy folder should say so at once, not wait for hours.
  if (::flock(lock_descriptor_, LOCK_EX | LOCK_NB) != 0) {
    const int lock_error = errno;
    const long holder = lock_holder(lock_descriptor_);
    ::close(lock_descriptor_);
    if (lock_error != EWOULDBLOCK) unusable_folder(directory_, "lock", lock_error);
    throw RunError(fmt::format(
        "the output folder '{}' is in use by another rktsph run{}; wait for it to finish or "
        "choose another folder with -o",
        directory_.string(), holder > 0 ? fmt::format(" (pid {})", holder) : ""));
  }
  record_holder(lock_descriptor_);
  try {
    remove_stale_temporaries();
    handle_existing_results(existing);
  } catch (...) {
    ::close(lock_descriptor_);
    throw;
  }
}

OutputFolder::~OutputFolder() {
  // The lock file stays: removing it would let a run that opened it just before lock a file no
  // longer in the folder while a third run locks a new one.
  ::close(lock_descriptor_);
}

// Holding the lock, any temporary here belongs to a run that no longer exists.
void OutputFolder::remove_stale_temporaries() {
  for (const fs::path& folder : {directory_, directory_ / "fields"}) {
    if (!is_real_directory(folder)) continue;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
      if (!is_temporary_file_name(entry.path().filename().string())) continue;
      if (is_real_directory(entry.path())) continue;
      std::error_code ignored;
      if (fs::remove(entry.path(), ignored)) ++removed_temporaries_;  // a symlink, not its target
    }
  }
}

// What a run leaves when its case or setup failed before the first field file: the resolved
// case, the log and the summary saying why. There is nothing computed in them to protect, and
// asking for --overwrite would only stand in the way of the corrected case.
bool only_a_setup_record(const std::vector<fs::path>& files) {
  return std::all_of(files.begin(), files.end(), [](const fs::path& file) {
    const std::string name = file.filename().string();
    return file.parent_path().filename() != "fields" &&
           (name == "summary.json" || name == "case.yaml" || name == "run.log");
  });
}

void OutputFolder::handle_existing_results(ExistingResults existing) {
  const std::vector<fs::path> files = run_result_files(directory_);
  if (files.empty() || existing == ExistingResults::Continue) return;
  if (existing == ExistingResults::Refuse && only_a_setup_record(files)) {
    replaced_setup_record_ = true;
    existing = ExistingResults::Overwrite;
  }
  if (existing == ExistingResults::Refuse)
    throw InputError({}, "", "",
                     fmt::format("the output folder '{}' holds the results of an earlier run ({})",
                                 directory_.string(), describe_results(files)),
                     "--overwrite to replace them, or another folder with -o");
  for (const fs::path& file : files) {
    std::error_code error;
    fs::remove(file, error);
    if (error)
      throw InputError(
          {}, "", "",
          fmt::format("cannot remove '{}' of the earlier run: {}", file.string(), error.message()),
          "");
    ++removed_results_;
  }
  std::error_code ignored;
  if (is_real_directory(directory_ / "fields"))
    fs::remove(directory_ / "fields", ignored);  // only if empty: other files in it stay
}

}  // namespace rktsph
