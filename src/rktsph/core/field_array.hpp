// Several scalar fields over one point set, structure-of-arrays: field f occupies the contiguous
// range [f * points, (f + 1) * points) of one buffer. Allocated once; the time step only reads
// and writes through pointers.
#pragma once

#include <cstddef>
#include <vector>

namespace rktsph {

class FieldArray {
 public:
  FieldArray() = default;
  FieldArray(int field_count, std::size_t point_count)
      : field_count_(field_count),
        point_count_(point_count),
        data_(static_cast<std::size_t>(field_count) * point_count, 0.0) {}

  int field_count() const { return field_count_; }
  std::size_t point_count() const { return point_count_; }

  double* field(int f) { return data_.data() + static_cast<std::size_t>(f) * point_count_; }
  const double* field(int f) const {
    return data_.data() + static_cast<std::size_t>(f) * point_count_;
  }
  double& operator()(int f, std::size_t i) { return field(f)[i]; }
  double operator()(int f, std::size_t i) const { return field(f)[i]; }

  std::vector<double>& data() { return data_; }
  const std::vector<double>& data() const { return data_; }

 private:
  int field_count_ = 0;
  std::size_t point_count_ = 0;
  std::vector<double> data_;
};

}  // namespace rktsph
