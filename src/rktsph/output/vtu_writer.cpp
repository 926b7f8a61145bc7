#include "rktsph/output/vtu_writer.hpp"

#include <array>
#include <bit>
#include <cstdint>
#include <stdexcept>

#include <fmt/format.h>

#include "rktsph/output/atomic_file.hpp"
#include "rktsph/output/base64.hpp"
#include "rktsph/output/xml_text.hpp"

namespace rktsph {

namespace {

constexpr std::uint8_t kVtkVertex = 1;

void check_input(const PointPositions& positions, std::span<const PointField> fields) {
  if (positions.dimension < 1 || positions.dimension > kMaxDimension) {
    throw std::invalid_argument(
        fmt::format("write_vtu: dimension {} is not 1, 2 or 3", positions.dimension));
  }
  const bool has_points = positions.count > 0;
  for (int axis = 0; axis < positions.dimension; ++axis) {
    if (has_points && positions.coordinates[axis] == nullptr) {
      throw std::invalid_argument(fmt::format("write_vtu: coordinate {} is null", axis));
    }
  }
  for (const PointField& field : fields) {
    if (field.components < 1 ||
        field.component_data.size() != static_cast<std::size_t>(field.components)) {
      throw std::invalid_argument(
          fmt::format("write_vtu: field '{}' declares {} components but has {} arrays", field.name,
                      field.components, field.component_data.size()));
    }
    for (const double* component : field.component_data) {
      if (has_points && component == nullptr) {
        throw std::invalid_argument(
            fmt::format("write_vtu: field '{}' has a null component array", field.name));
      }
    }
  }
}

// The binary layout of an uncompressed inline array is one base64 stream holding the byte count
// of the data (UInt64, as declared by header_type) followed by the data itself.
void open_data_array(std::ostream& out, std::string_view type, std::string_view name,
                     int components, std::span<const char* const> component_names = {}) {
  out << "        <DataArray type=\"" << type << "\"";
  if (!name.empty()) out << " Name=\"" << escape_xml_attribute(name) << "\"";
  out << " NumberOfComponents=\"" << components << "\"";
  // VTK's XML readers take ComponentName<i> as the name of component i; ParaView lists those
  // names (XX, XY, ...) instead of the indices 0-8.
  for (std::size_t i = 0; i < component_names.size(); ++i)
    out << " ComponentName" << i << "=\"" << component_names[i] << "\"";
  out << " format=\"binary\">\n          ";
}

// Names for the documented component orders of PointField: x y z for a vector, row order for a
// 3 x 3 tensor. Other counts stay unnamed (ParaView shows indices).
std::span<const char* const> component_names(int components) {
  static constexpr std::array<const char*, 3> kVector = {"X", "Y", "Z"};
  static constexpr std::array<const char*, 9> kTensor = {"XX", "XY", "XZ", "YX", "YY",
                                                         "YZ", "ZX", "ZY", "ZZ"};
  if (components == 3) return kVector;
  if (components == 9) return kTensor;
  return {};
}

void close_data_array(std::ostream& out) {
  out << "\n        </DataArray>\n";
}

void write_point_field(std::ostream& out, std::size_t count, const PointField& field) {
  open_data_array(out, "Float64", field.name, field.components, component_names(field.components));
  Base64Encoder encoder(out);
  encoder.put_little_endian(count * static_cast<std::size_t>(field.components) * sizeof(double));
  for (std::size_t point = 0; point < count; ++point) {
    for (const double* component : field.component_data) {
      encoder.put_little_endian(std::bit_cast<std::uint64_t>(component[point]));
    }
  }
  encoder.finish();
  close_data_array(out);
}

void write_points(std::ostream& out, const PointPositions& positions) {
  out << "      <Points>\n";
  open_data_array(out, "Float64", "Points", 3);
  Base64Encoder encoder(out);
  encoder.put_little_endian(positions.count * 3 * sizeof(double));
  for (std::size_t point = 0; point < positions.count; ++point) {
    for (int axis = 0; axis < kMaxDimension; ++axis) {
      const double coordinate =
          axis < positions.dimension ? positions.coordinates[axis][point] : 0.0;
      encoder.put_little_endian(std::bit_cast<std::uint64_t>(coordinate));
    }
  }
  encoder.finish();
  close_data_array(out);
  out << "      </Points>\n";
}

// One VTK_VERTEX per point: cell i holds point i, so connectivity is 0..n-1 and the offset (one
// past the end of each cell's connectivity) is i+1.
void write_vertex_cells(std::ostream& out, std::size_t count) {
  out << "      <Cells>\n";
  const std::uint64_t int64_bytes = count * sizeof(std::int64_t);
  for (const std::uint64_t first : {std::uint64_t{0}, std::uint64_t{1}}) {
    open_data_array(out, "Int64", first == 0 ? "connectivity" : "offsets", 1);
    Base64Encoder encoder(out);
    encoder.put_little_endian(int64_bytes);
    for (std::uint64_t index = 0; index < count; ++index)
      encoder.put_little_endian(index + first);
    encoder.finish();
    close_data_array(out);
  }
  open_data_array(out, "UInt8", "types", 1);
  Base64Encoder encoder(out);
  encoder.put_little_endian(count);
  for (std::size_t index = 0; index < count; ++index)
    encoder.put(kVtkVertex);
  encoder.finish();
  close_data_array(out);
  out << "      </Cells>\n";
}

}  // namespace

PointPositions positions_of(const PointCloud& cloud) {
  PointPositions positions;
  positions.dimension = cloud.dimension;
  positions.count = cloud.size();
  for (int axis = 0; axis < kMaxDimension; ++axis) {
    positions.coordinates[axis] =
        cloud.position[axis].size() >= cloud.size() ? cloud.position[axis].data() : nullptr;
  }
  return positions;
}

void write_vtu(std::ostream& out, const PointPositions& positions,
               std::span<const PointField> fields) {
  check_input(positions, fields);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\""
      << " header_type=\"UInt64\">\n"
      << "  <UnstructuredGrid>\n"
      << "    <Piece NumberOfPoints=\"" << positions.count << "\" NumberOfCells=\""
      << positions.count << "\">\n"
      << "      <PointData>\n";
  for (const PointField& field : fields)
    write_point_field(out, positions.count, field);
  out << "      </PointData>\n";
  write_points(out, positions);
  write_vertex_cells(out, positions.count);
  out << "    </Piece>\n"
      << "  </UnstructuredGrid>\n"
      << "</VTKFile>\n";
}

void write_vtu(const std::filesystem::path& path, const PointPositions& positions,
               std::span<const PointField> fields) {
  // Checked before the file is opened so that bad input leaves no file behind at all.
  check_input(positions, fields);
  write_file_atomically(path, [&](std::ostream& out) { write_vtu(out, positions, fields); });
}

void write_vtu(const std::filesystem::path& path, const PointCloud& cloud,
               std::span<const PointField> fields) {
  write_vtu(path, positions_of(cloud), fields);
}

}  // namespace rktsph
