#include "rktsph/stabilisation/patch_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "rktsph/core/parallel.hpp"

namespace rktsph {

namespace {

// Which of the functions (1, x - x_n, y - y_n) a field of `parity` may use on a node lying on the
// mirror planes `planes`: a function's parity across those planes must be the field's (eq. 3.13).
std::array<bool, 3> allowed_functions(Parity parity, std::uint8_t planes) {
  const unsigned field = static_cast<unsigned>(parity) & planes;
  return {field == 0u, (1u & planes) == field, (2u & planes) == field};
}

// Moore-Penrose inverse of the symmetric 3 x 3 `normal` on its allowed rows and columns: the
// directions a patch does not determine (eigenvalues below 1e-10 of the largest) are left out,
// so that the fit stays a projection.
std::array<double, 9> pseudo_inverse(const Eigen::Matrix3d& normal) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(normal);
  const Eigen::Vector3d values = solver.eigenvalues();
  const double largest = values.cwiseAbs().maxCoeff();
  Eigen::Vector3d inverse = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k)
    if (largest > 0.0 && values[k] > 1e-10 * largest) inverse[k] = 1.0 / values[k];
  const Eigen::Matrix3d result =
      solver.eigenvectors() * inverse.asDiagonal() * solver.eigenvectors().transpose();
  std::array<double, 9> out{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      out[static_cast<std::size_t>(r * 3 + c)] = result(r, c);
  return out;
}

}  // namespace

PatchFit::PatchFit(const CellComplex& cells, const PointCloud& nodes, const PointCloud& points,
                   std::span<const std::uint8_t> mirror_axes, std::span<const Parity> parity)
    : cells_(&cells),
      nodes_(&nodes),
      points_(&points),
      field_parity_(parity.begin(), parity.end()) {
  if (field_parity_.size() > kMaxFields)
    throw std::invalid_argument("PatchFit: at most kMaxFields fields");
  for (Parity p : field_parity_) {
    auto known = std::find(class_parity_.begin(), class_parity_.end(), p);
    if (known == class_parity_.end()) known = class_parity_.insert(class_parity_.end(), p);
    field_class_.push_back(static_cast<std::size_t>(known - class_parity_.begin()));
  }
  const std::size_t node_count = nodes.size();
  inverse_normal_.resize(node_count * class_parity_.size());
  for (std::size_t n = 0; n < node_count; ++n)
    for (std::size_t k = 0; k < class_parity_.size(); ++k) {
      const std::array<bool, 3> allowed = allowed_functions(class_parity_[k], mirror_axes[n]);
      Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
      for (std::int32_t cell : cells.cells_of(n)) {
        const auto p = static_cast<std::size_t>(cell);
        const double weight =
            points.volume[p] / static_cast<double>(cells.corners(p).size());  // c_Pn
        const std::array<double, 3> phi = basis(n, p);
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c)
            if (allowed[static_cast<std::size_t>(r)] && allowed[static_cast<std::size_t>(c)])
              normal(r, c) +=
                  weight * phi[static_cast<std::size_t>(r)] * phi[static_cast<std::size_t>(c)];
      }
      inverse_normal_[n * class_parity_.size() + k] = pseudo_inverse(normal);
    }
  coefficient_.resize(node_count);
}

std::array<double, 3> PatchFit::basis(std::size_t node, std::size_t point) const {
  return {1.0, points_->position[0][point] - nodes_->position[0][node],
          points_->position[1][point] - nodes_->position[1][node]};
}

void PatchFit::residual(const FieldArray& values, FieldArray& residual) const {
  const int fields = static_cast<int>(field_parity_.size());
  const auto node_count = static_cast<std::int64_t>(nodes_->size());
  const std::size_t classes = class_parity_.size();
  // The fits: (a, b) = N^+ sum_P c_Pn phi(x_P) s_P at every node, all fields in one pass over the
  // patch.
#pragma omp parallel for schedule(static) if (node_count > kParallelThreshold)
  for (std::int64_t node = 0; node < node_count; ++node) {
    const auto n = static_cast<std::size_t>(node);
    std::array<std::array<double, 3>, kMaxFields> moment{};
    for (std::int32_t cell : cells_->cells_of(n)) {
      const auto p = static_cast<std::size_t>(cell);
      const double share = points_->volume[p] / static_cast<double>(cells_->corners(p).size());
      const std::array<double, 3> phi = basis(n, p);
      for (int f = 0; f < fields; ++f) {
        const double weight = share * values(f, p);
        for (std::size_t r = 0; r < 3; ++r)
          moment[static_cast<std::size_t>(f)][r] += weight * phi[r];
      }
    }
    for (int f = 0; f < fields; ++f) {
      const std::array<double, 9>& inverse =
          inverse_normal_[n * classes + field_class_[static_cast<std::size_t>(f)]];
      const std::array<double, 3>& m = moment[static_cast<std::size_t>(f)];
      for (std::size_t r = 0; r < 3; ++r)
        coefficient_[n][3 * static_cast<std::size_t>(f) + r] =
            inverse[r * 3] * m[0] + inverse[r * 3 + 1] * m[1] + inverse[r * 3 + 2] * m[2];
    }
  }
  // rho_P = s_P - mean over the corners n of f_n(x_P).
  const auto point_count = static_cast<std::int64_t>(points_->size());
#pragma omp parallel for schedule(static) if (point_count > kParallelThreshold)
  for (std::int64_t point = 0; point < point_count; ++point) {
    const auto p = static_cast<std::size_t>(point);
    const std::span<const std::int32_t> corners = cells_->corners(p);
    const double share = 1.0 / static_cast<double>(corners.size());
    std::array<double, kMaxFields> fitted{};
    for (std::int32_t corner : corners) {
      const auto n = static_cast<std::size_t>(corner);
      const std::array<double, 3> phi = basis(n, p);
      const std::array<double, 3 * kMaxFields>& c = coefficient_[n];
      for (std::size_t f = 0; f < static_cast<std::size_t>(fields); ++f)
        fitted[f] += c[3 * f] * phi[0] + c[3 * f + 1] * phi[1] + c[3 * f + 2] * phi[2];
    }
    for (int f = 0; f < fields; ++f)
      residual(f, p) = values(f, p) - share * fitted[static_cast<std::size_t>(f)];
  }
}

}  // namespace rktsph
