// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Checks and inverses of the metric tensors given to the fast-sweeping solvers.
//
// Positive definiteness is decided by a Cholesky factorisation M = L L^T, not by the determinant:
// for a rounded matrix with eigenvalues (1, 1, 1e12) the determinant may come out negative (it
// depends on the evaluation order, e.g. FMA), while the factorisation succeeds.  In floating point
// the factorisation is the standard test (it succeeds for every matrix whose eigenvalues are all
// well above the rounding error of its entries).  A matrix whose pivots span more than the double
// precision range (min pivot < N eps max pivot) carries no information about its soft directions:
// it is numerically singular and rejected too.  The inverse is solved from the same factorisation
// (the cofactor formula loses everything at condition numbers around 1e10).
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_METRIC_TENSOR_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_METRIC_TENSOR_H

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// Null if `M` is a symmetric positive definite matrix (up to the symmetry tolerance), otherwise
// what is wrong with it, to be completed by the caller with the node it was given at.
template <int N>
const char* metric_defect(const Eigen::Matrix<double, N, N>& M)
{
  if(!M.allFinite()) return "has a non-finite entry";
  const double scale = M.cwiseAbs().maxCoeff();
  if((M - M.transpose()).cwiseAbs().maxCoeff() > 1e-10 * scale) return "is not symmetric";
  // Cholesky factorisation of the symmetric part, L L^T, written out (it runs once per grid node):
  // the pivots are the squared diagonal entries of L.
  Eigen::Matrix<double, N, N> L = 0.5 * (M + M.transpose());
  double min_pivot = std::numeric_limits<double>::infinity(), max_pivot = 0.;
  for(int j = 0; j < N; ++j)
  {
    double pivot = L(j, j);
    for(int k = 0; k < j; ++k) pivot -= L(j, k) * L(j, k);
    if(!(pivot > 0.)) return "is not positive definite (its Cholesky factorisation fails)";
    min_pivot = std::min(min_pivot, pivot);
    max_pivot = std::max(max_pivot, pivot);
    L(j, j) = std::sqrt(pivot);
    for(int i = j + 1; i < N; ++i)
    {
      double sum = L(i, j);
      for(int k = 0; k < j; ++k) sum -= L(i, k) * L(j, k);
      L(i, j) = sum / L(j, j);
    }
  }
  if(!(min_pivot > N * std::numeric_limits<double>::epsilon() * max_pivot))
    return "is numerically singular (condition number beyond 1/epsilon of double precision)";
  return nullptr;
}

// Message of the solvers for a metric rejected by `metric_defect()`.
template <int N>
std::string metric_error_message(const std::string& solver, const std::string& node, const std::string& defect,
                                 const Eigen::Matrix<double, N, N>& M)
{
  std::ostringstream os;
  os.precision(17);
  os << solver << ": the metric at " << node << " " << defect << ": [";
  for(int r = 0; r < N; ++r)
    for(int c = 0; c < N; ++c) os << M(r, c) << (c + 1 < N ? " " : (r + 1 < N ? "; " : "]"));
  os << "; give a symmetric positive definite matrix at every node (e.g. w I + w' III with w > 0)";
  return os.str();
}

// Inverse of a metric accepted by `metric_defect()`, from its Cholesky factorisation, symmetric.
template <int N>
Eigen::Matrix<double, N, N> metric_inverse(const Eigen::Matrix<double, N, N>& M)
{
  using Matrix = Eigen::Matrix<double, N, N>;
  const Matrix inverse = Eigen::LLT<Matrix>(0.5 * (M + M.transpose())).solve(Matrix::Identity());
  return 0.5 * (inverse + inverse.transpose());
}

} // namespace internal
} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_INTERNAL_METRIC_TENSOR_H
