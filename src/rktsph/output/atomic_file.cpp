#include "rktsph/output/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <streambuf>
#include <system_error>
#include <vector>

#include <fmt/format.h>

#include "rktsph/core/error.hpp"

namespace rktsph {

namespace {

[[noreturn]] void fail(const std::string& action, const std::filesystem::path& path,
                       int error_number) {
  throw RunError(fmt::format("cannot {} '{}': {}", action, path.string(),
                             describe_system_error(error_number)));
}

// An output stream buffer over a file descriptor that keeps the errno of the first failed
// write. std::ofstream does not say why it failed (errno is often 0 or stale by the time the
// stream reports), which is how a full disk came out as "unknown I/O error".
class DescriptorBuffer final : public std::streambuf {
 public:
  explicit DescriptorBuffer(int descriptor) : descriptor_(descriptor), buffer_(1 << 16) {
    reset_put_area();
  }
  int error() const { return error_; }

 protected:
  int_type overflow(int_type character) override {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(character, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(character);
      pbump(1);
    }
    return traits_type::not_eof(character);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  void reset_put_area() { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
  bool drain() {
    if (error_ != 0) return false;
    const char* data = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0) {
      const ssize_t written = ::write(descriptor_, data, left);
      if (written < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      data += written;
      left -= static_cast<std::size_t>(written);
    }
    reset_put_area();
    return true;
  }

  int descriptor_;
  std::vector<char> buffer_;
  int error_ = 0;
};

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

struct Temporary {
  int descriptor;
  std::filesystem::path path;
};

// O_EXCL | O_NOFOLLOW: whatever is already under the name (a stale file, a planted symlink) is
// left alone and the next name is tried, so the data can only ever land in a new regular file.
Temporary create_temporary(const std::filesystem::path& path) {
  constexpr int kAttempts = 100;
  const std::filesystem::path first = temporary_path_for(path);
  for (int attempt = 0; attempt < kAttempts; ++attempt) {
    std::filesystem::path candidate = first;
    if (attempt > 0) candidate += fmt::format("-{}", attempt);
    const int descriptor =
        ::open(candidate.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (descriptor >= 0) return {descriptor, candidate};
    if (errno != EEXIST) fail("create", candidate, errno);
  }
  fail("create", first, EEXIST);
}

// Without fsync before the rename, a power loss could leave the new name pointing at an empty or
// partial file on some file systems (ext4 with delayed allocation, for one).
void write_sync_and_close(Temporary& temporary, const std::function<void(std::ostream&)>& write) {
  write_to_descriptor(temporary.descriptor, temporary.path, write);
  if (::fsync(temporary.descriptor) != 0) fail("fsync", temporary.path, errno);
  const int descriptor = temporary.descriptor;
  temporary.descriptor = -1;
  if (::close(descriptor) != 0) fail("close", temporary.path, errno);
}

bool all_digits(std::string_view text) {
  if (text.empty()) return false;
  for (const char c : text)
    if (c < '0' || c > '9') return false;
  return true;
}

}  // namespace

std::string describe_system_error(int error_number) {
  if (error_number == 0) return "unknown I/O error";
  return std::error_code(error_number, std::generic_category()).message();
}

void write_to_descriptor(int descriptor, const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write) {
  DescriptorBuffer buffer(descriptor);
  std::ostream stream(&buffer);
  write(stream);
  stream.flush();
  if (!stream) fail("write", path, buffer.error());
}

std::filesystem::path temporary_path_for(const std::filesystem::path& path) {
  std::filesystem::path temporary = path;
  temporary += fmt::format(".tmp-{}", static_cast<long>(::getpid()));
  return temporary;
}

bool is_temporary_file_name(std::string_view file_name) {
  const std::size_t marker = file_name.rfind(".tmp-");
  if (marker == std::string_view::npos || marker == 0) return false;
  const std::string_view suffix = file_name.substr(marker + 5);
  const std::size_t dash = suffix.find('-');
  if (dash == std::string_view::npos) return all_digits(suffix);
  return all_digits(suffix.substr(0, dash)) && all_digits(suffix.substr(dash + 1));
}

void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write) {
  Temporary temporary = create_temporary(path);
  try {
    write_sync_and_close(temporary, write);
    if (std::rename(temporary.path.c_str(), path.c_str()) != 0) {
      const int rename_error = errno;
      throw RunError(fmt::format("cannot rename '{}' to '{}': {}", temporary.path.string(),
                                 path.string(), describe_system_error(rename_error)));
    }
  } catch (...) {
    if (temporary.descriptor >= 0) ::close(temporary.descriptor);
    ::unlink(temporary.path.c_str());
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
