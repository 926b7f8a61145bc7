// Whole-file replacement that a crash cannot leave half-written.
//
// Every result file except run.log is produced by rewriting it completely, so a reader (ParaView,
// a plotting script, a restarted run) must only ever see either the previous complete version or
// the new complete version. The content goes to a temporary file in the same directory (so the
// final rename stays within one file system and is atomic), is flushed to disk, and only then is
// renamed over the final name.
#pragma once

#include <filesystem>
#include <functional>
#include <ostream>
#include <string>

namespace rktsph {

/// Writes what `write` produces to `path`, atomically.
///
/// The temporary file is `path` + ".tmp-<pid>". On an I/O failure (cannot create, write, fsync
/// or rename) the temporary file is removed and a RunError naming the path and the OS error is
/// thrown; `path` is untouched. If `write` itself throws, the temporary file is removed and that
/// exception propagates unchanged, since it says more than a generic I/O message would.
/// Not meant for two threads of one process writing the same path at the same time.
void write_file_atomically(const std::filesystem::path& path,
                           const std::function<void(std::ostream&)>& write);

/// Same, with the whole content given as a string.
void write_file_atomically(const std::filesystem::path& path, const std::string& content);

/// The name of the temporary file used for `path` by this process (exposed for tests).
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

}  // namespace rktsph
