#include "rktsph/output/pvd_writer.hpp"

#include <algorithm>
#include <utility>

#include <fmt/format.h>

#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/xml_text.hpp"

namespace rktsph {

PvdCollection::PvdCollection(std::filesystem::path pvd_path) : pvd_path_(std::move(pvd_path)) {}

void PvdCollection::add(double time, std::string file) {
  std::erase_if(entries_, [&file](const Entry& entry) { return entry.file == file; });
  const auto position =
      std::upper_bound(entries_.begin(), entries_.end(), time,
                       [](double new_time, const Entry& entry) { return new_time < entry.time; });
  entries_.insert(position, Entry{time, std::move(file)});
  write();
}

void PvdCollection::write() const {
  write_file_atomically(pvd_path_, to_string());
}

std::string PvdCollection::to_string() const {
  std::string document =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const Entry& entry : entries_) {
    // Shortest round-trip form: readable, and two outputs at nearby times never share a timestep.
    document += fmt::format("    <DataSet timestep=\"{}\" group=\"\" part=\"0\" file=\"{}\"/>\n",
                            entry.time, escape_xml_attribute(entry.file));
  }
  document +=
      "  </Collection>\n"
      "</VTKFile>\n";
  return document;
}

}  // namespace rktsph
