// VTK XML UnstructuredGrid (.vtu) files of point clouds, for ParaView.
//
// Every point is its own VTK_VERTEX cell, so filters that need cells (Glyph, Threshold) work.
// All arrays are inline base64 binary with a UInt64 byte-count header, little-endian, Float64
// for point data: exact values, no extra files, and no byte-order surprises.
#pragma once

#include <array>
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <span>
#include <string>
#include <vector>

#include "rktsph/core/point_cloud.hpp"

namespace rktsph {

/// One point-data array in structure-of-arrays form: component_data[c][i] is component c of
/// point i. The file stores it interleaved per point, as VTK expects. For a 9-component tensor
/// pass the components in the order xx xy xz yx yy yz zx zy zz; the file names them XX, XY, ...
/// ZZ (and the components of a 3-vector X, Y, Z), which ParaView shows.
struct PointField {
  std::string name;
  int components = 1;
  std::vector<const double*> component_data;
};

/// Point coordinates in structure-of-arrays form. Only coordinates[a] with a < dimension are
/// read; the others are written as zeros, since VTK points always have three coordinates.
struct PointPositions {
  int dimension = 3;
  std::size_t count = 0;
  std::array<const double*, kMaxDimension> coordinates{};
};

/// Views the positions of a point cloud (no copy; the cloud must outlive the result's use).
PointPositions positions_of(const PointCloud& cloud);

/// Writes the .vtu document to a stream. Throws std::invalid_argument for inconsistent input
/// (dimension outside 1..3, a component count below 1 or not matching component_data, a null
/// pointer for a non-empty cloud): those are programming errors, not user errors.
void write_vtu(std::ostream& out, const PointPositions& positions,
               std::span<const PointField> fields);

/// Writes the .vtu file atomically (see atomic_file.hpp); throws RunError on I/O failure.
void write_vtu(const std::filesystem::path& path, const PointPositions& positions,
               std::span<const PointField> fields);
void write_vtu(const std::filesystem::path& path, const PointCloud& cloud,
               std::span<const PointField> fields);

}  // namespace rktsph
