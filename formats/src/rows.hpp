// Fixed-size vectors per row of a dataset, for the typed readers and writers of formats/
// (internal to the formats library).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tfmb/common/h5.hpp"

namespace tfmb::formats::detail {

// (n, N) matrix of n vectors of size N.
template <int N>
h5::MatrixXdR rows(const std::vector<Eigen::Matrix<double, N, 1>>& v) {
  h5::MatrixXdR m(static_cast<Eigen::Index>(v.size()), N);
  for (std::size_t i = 0; i < v.size(); ++i)
    m.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  return m;
}

// A dataset of `count` rows of N values (the reader's shape check names the path).
template <int N>
std::vector<Eigen::Matrix<double, N, 1>> read_rows(const h5::Reader& r, const std::string& path,
                                                   std::size_t count) {
  const h5::MatrixXdR m = r.read_matrix(path, static_cast<Eigen::Index>(count), N);
  std::vector<Eigen::Matrix<double, N, 1>> out(count);
  for (std::size_t i = 0; i < count; ++i)
    out[i] = m.row(static_cast<Eigen::Index>(i)).transpose();
  return out;
}

}  // namespace tfmb::formats::detail
