// ParaView collection (.pvd) file that ties the per-output .vtu files to simulated times.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace rktsph {

class PvdCollection {
 public:
  struct Entry {
    double time = 0.0;
    /// Relative to the directory of the .pvd file, as ParaView resolves it.
    std::string file;
  };

  /// Nothing is written until the first add().
  explicit PvdCollection(std::filesystem::path pvd_path);

  /// Records `file` at `time` and rewrites the whole collection atomically, so that after a
  /// crash the .pvd lists exactly the data files completed so far. Entries are kept in time order
  /// (equal times keep insertion order); adding a file name already listed replaces its time, so
  /// a rewritten output file is not listed twice. Throws RunError on I/O failure.
  void add(double time, std::string file);

  const std::vector<Entry>& entries() const { return entries_; }
  /// Replaces the entries (a restarted run's, from its checkpoint) without writing the file.
  void set_entries(std::vector<Entry> entries) { entries_ = std::move(entries); }
  /// Rewrites the whole collection atomically with the current entries.
  void write() const;
  const std::filesystem::path& path() const { return pvd_path_; }

  /// The document for the current entries.
  std::string to_string() const;

 private:
  std::filesystem::path pvd_path_;
  std::vector<Entry> entries_;
};

}  // namespace rktsph
