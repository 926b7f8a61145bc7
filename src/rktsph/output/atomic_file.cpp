#include "rktsph/output/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <fstream>
#include <system_error>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"

namespace rktsph {

namespace {

std::string describe_errno(int error_number) {
  if (error_number == 0) return "unknown I/O error";
  return std::error_code(error_number, std::generic_category()).message();
}

[[noreturn]] void fail(const std::string& action, const std::filesystem::path& path,
                       int error_number) {
  throw RunError(
      fmt::format("cannot {} '{}': {}", action, path.string(), describe_errno(error_number)));
}

// Without fsync before the rename, a power loss could leave the new name pointing at an empty or
// partial file on some file systems (ext4 with delayed allocation, for one).
void sync_file(const std::filesystem::path& path) {
  errno = 0;
  const int descriptor = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
  if (descriptor < 0) fail("open for fsync", path, errno);
  const bool synced = ::fsync(descriptor) == 0;
  const int sync_error = errno;
  ::close(descriptor);
  if (!synced) fail("fsync", path, sync_error);
}

// Makes the rename itself durable. Best effort: some file systems refuse fsync on a directory,
// and the new file is already complete on disk, so a failure here is not worth stopping a run.
void sync_directory_best_effort(const std::filesystem::path& directory) {
  const int descriptor = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (descriptor < 0) return;
  ::fsync(descriptor);
  ::close(descriptor);
}

std::filesystem::path directory_of(const std::filesystem::path& path) {
  const std::filesystem::path parent = path.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

void write_temporary(const std::filesystem::path& temporary,
                     const std::function<void(std::ostream&)>& write) {
  errno = 0;
  std::ofstream stream(temporary, std::ios::binary | std::ios::trunc);
  if (!stream) fail("create", temporary, errno);
  write(stream);
  errno = 0;
  stream.flush();
  if (!stream) fail("write", temporary, errno);
  stream.close();
  if (stream.fail()) fail("close", temporary, errno);
}

}  // namespace

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  return temporary;
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path temporary = temporary_path_for(path);
  try {
    write_temporary(temporary, write);
    sync_file(temporary);
    std::error_code rename_error;
    std::filesystem::rename(temporary, path, rename_error);
    if (rename_error) {
      throw RunError(fmt::format("cannot rename '{}' to '{}': {}", temporary.string(),
                                 path.string(), rename_error.message()));
    }
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(temporary, ignored);
    throw;
  }
  sync_directory_best_effort(directory_of(path));
}

void write_file_atomically(const std::filesystem::path& path, const std::string& content) {
  write_file_atomically(path, [&content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

}  // namespace rktsph
