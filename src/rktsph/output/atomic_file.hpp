// Whole-file replacement that a crash cannot leave half-written, and that a planted symlink
// cannot redirect.
//
// Every result file except run.log is produced by rewriting it completely, so a reader (ParaView,
// a plotting script, a restarted run) must only ever see either the previous complete version or
// the new complete version. The content goes to a temporary file in the same directory (so the
// final rename stays within one file system and is atomic), is flushed to disk, and only then is
// renamed over the final name. The temporary is created exclusively (O_CREAT | O_EXCL |
// O_NOFOLLOW): a file or symlink already there under that name is never opened, written or
// followed, and the rename replaces a symlink at the final name by the regular file.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace rktsph {

/// Writes what `write` produces to `path`, atomically.
///
/// The temporary file is `path` + ".tmp-<pid>", or ".tmp-<pid>-<n>" when a file of that name is
/// already there. On an I/O failure (cannot create, write, fsync or rename) the temporary file is
/// removed and a RunError naming the path and the system's reason ("No space left on device")
/// is thrown; `path` is untouched. If `write` itself throws, the temporary file is removed and
/// that exception propagates unchanged, since it says more than a generic I/O message would.
/// Not meant for two threads of one process writing the same path at the same time.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

/// Same, with the whole content given as a string.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

/// The name of the first temporary file tried for `path` by this process (exposed for tests).
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

/// True for the names write_file_atomically gives its temporaries ("<name>.tmp-<digits>" or
/// "<name>.tmp-<digits>-<digits>"): what a killed run leaves behind.
bool is_temporary_file_name(std::string_view file_name);

/// Streams what `write` produces into the open file `descriptor` and flushes it; RunError
/// "cannot write '<path>': <system reason>" if a write fails (`path` only names the file in the
/// message). The building block of write_file_atomically, exposed so that a test can aim it at
/// /dev/full.
void write_to_descriptor(int descriptor, const std::filesystem::path& path,
                         const std::function<void(std::ostream&)>& write);

/// The system's text for an errno value ("No space left on device"), or "unknown I/O error"
/// for 0.
std::string describe_system_error(int error_number);

}  // namespace rktsph
