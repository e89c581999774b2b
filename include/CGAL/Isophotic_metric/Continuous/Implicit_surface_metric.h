// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Isophotic metric of an implicit surface F(x) = 0 (Pottmann et al. 2004, Sect. 2.2):
//   n = grad F / |grad F|,  J = Dn,  N = J^T J,  M = w E + w' N   (a metric on R^3).
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_IMPLICIT_SURFACE_METRIC_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_IMPLICIT_SURFACE_METRIC_H

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_3.h>
#include <CGAL/Isophotic_metric/Continuous/Parametric_surface_metric.h> // check_isophotic_weights
#include <CGAL/Isophotic_metric/exceptions.h>

#include <Eigen/Dense>

#include <cmath>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// How the metric is extended off the surface `F = 0` into the narrow band.
enum class Implicit_metric_extension
{
  /// `M = w E + w' N` everywhere, as in the paper.  Exact on the surface, but inside a band of
  /// half-width `b` a path may run on a parallel surface where the Euclidean part is shorter
  /// (on the concave side), an error of order `b` times the curvature.
  paper,
  /// Default.  `M = w (P^T P + n n^T) + w' N` with `P = D(x - phi n)` the derivative of the foot point
  /// map, `phi = F/|grad F|`: every parallel surface carries the metric of its foot points on
  /// `F = 0` (the Gaussian map is the same on parallel surfaces), and moving across costs `w`.
  /// Equal to the paper's metric on the surface itself, and removes the band-width error.
  foot_point
};

/// \ingroup PkgIsophoticMetricContinuousRef
/// Value, gradient and derivatives of the normal field of an implicit function at a point.
struct Implicit_differentials
{
  double value = 0.;
  Eigen::Vector3d gradient, normal;
  Eigen::Matrix3d hessian;
  Eigen::Matrix3d normal_jacobian;  ///< J = Dn = (E - n n^T) H / |grad F|
  Eigen::Matrix3d isophotic_form;   ///< N = J^T J
};

namespace internal {

template <typename F, typename = void>
struct has_gradient : std::false_type {};
template <typename F>
struct has_gradient<F, std::void_t<decltype(std::declval<const F&>().gradient(Eigen::Vector3d()))>> : std::true_type {};
template <typename F, typename = void>
struct has_hessian : std::false_type {};
template <typename F>
struct has_hessian<F, std::void_t<decltype(std::declval<const F&>().hessian(Eigen::Vector3d()))>> : std::true_type {};

} // namespace internal

/// \ingroup PkgIsophoticMetricContinuousRef
/// Completes value, gradient and Hessian into the normal, its Jacobian `J` and `N = J^T J`.
/// \throws Invalid_parameter_error if the gradient vanishes or a value is not finite
inline Implicit_differentials implicit_differentials_from(double value, const Eigen::Vector3d& gradient,
                                                          const Eigen::Matrix3d& hessian, const Eigen::Vector3d& x)
{
  Implicit_differentials id;
  id.value = value;
  id.gradient = gradient;
  id.hessian = hessian;
  const double g = gradient.norm();
  if(!std::isfinite(value) || !gradient.allFinite() || !hessian.allFinite() || !(g > 0.))
  {
    std::ostringstream os;
    os << "implicit function: non-finite value or derivative, or vanishing gradient, at x = (" << x.transpose() << ")";
    throw Invalid_parameter_error(os.str());
  }
  id.normal = gradient / g;
  const Eigen::Matrix3d tangential = Eigen::Matrix3d::Identity() - id.normal * id.normal.transpose();
  id.normal_jacobian = tangential * hessian / g;
  id.isophotic_form = id.normal_jacobian.transpose() * id.normal_jacobian;
  return id;
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// Differentials of a model of `ImplicitFunction` at `x` (its own derivatives when provided,
/// central differences otherwise).
template <typename ImplicitFunction>
Implicit_differentials implicit_differentials(const ImplicitFunction& F, const Eigen::Vector3d& x)
{
  const double value = F(x);
  Eigen::Vector3d gradient;
  Eigen::Matrix3d hessian;
  if constexpr(internal::has_gradient<ImplicitFunction>::value)
    gradient = F.gradient(x);
  else
  {
    const double h = 6e-6 * (1. + x.cwiseAbs().maxCoeff());
    for(int a = 0; a < 3; ++a)
    {
      const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(a);
      gradient[a] = (F(x + e) - F(x - e)) / (2. * h);
    }
  }
  if constexpr(internal::has_hessian<ImplicitFunction>::value)
    hessian = F.hessian(x);
  else
  {
    const double h = 1.2e-4 * (1. + x.cwiseAbs().maxCoeff());
    for(int a = 0; a < 3; ++a)
      for(int b = a; b < 3; ++b)
      {
        const Eigen::Vector3d ea = h * Eigen::Vector3d::Unit(a), eb = h * Eigen::Vector3d::Unit(b);
        hessian(a, b) = hessian(b, a) = (F(x + ea + eb) - F(x + ea - eb) - F(x - ea + eb) + F(x - ea - eb)) / (4. * h * h);
      }
  }
  return implicit_differentials_from(value, gradient, hessian, x);
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// The isophotic metric tensor on R^3 at a point with differentials `id`
/// (see `Implicit_metric_extension`).
/// \throws Invalid_parameter_error on invalid weights
inline Eigen::Matrix3d implicit_isophotic_metric_tensor(const Implicit_differentials& id, double w, double w_prime,
                                                         Implicit_metric_extension extension = Implicit_metric_extension::foot_point)
{
  check_isophotic_weights(w, w_prime);
  const Eigen::Matrix3d nn = id.normal * id.normal.transpose();
  if(extension == Implicit_metric_extension::paper)
    return w * Eigen::Matrix3d::Identity() + w_prime * id.isophotic_form;
  const double offset = id.value / id.gradient.norm();
  const Eigen::Matrix3d foot = Eigen::Matrix3d::Identity() - nn - offset * id.normal_jacobian;
  const Eigen::Matrix3d M = w * (foot.transpose() * foot + nn) + w_prime * id.isophotic_form;
  return 0.5 * (M + M.transpose());
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// `implicit_isophotic_metric_tensor()` of a model of `ImplicitFunction` at `x`.
template <typename ImplicitFunction>
Eigen::Matrix3d implicit_isophotic_metric_tensor(const ImplicitFunction& F, const Eigen::Vector3d& x, double w,
                                                 double w_prime,
                                                 Implicit_metric_extension extension = Implicit_metric_extension::foot_point)
{
  return implicit_isophotic_metric_tensor(implicit_differentials(F, x), w, w_prime, extension);
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// An implicit function sampled at the nodes of a `Grid_3` (e.g. a signed distance grid).
/// Evaluation is trilinear; differentials at the nodes use the grid's central differences.
/// The samples are checked when the function is made and cannot be changed afterwards.
class Sampled_function_3
{
public:
  /// \param grid the grid of the samples
  /// \param values one finite value per node of `grid`, indexed by `grid.index(i,j,k)`
  /// \throws Invalid_parameter_error if the number of values is not the number of nodes, or a value
  ///         is not finite (the message names the node)
  Sampled_function_3(const Grid_3& grid, std::vector<double> values) : grid_(grid), values_(std::move(values))
  {
    if(values_.size() != grid_.size())
      throw Invalid_parameter_error("Sampled_function_3: " + std::to_string(values_.size()) + " values for "
                                    + std::to_string(grid_.size()) + " nodes (" + std::to_string(grid_.nx()) + " x "
                                    + std::to_string(grid_.ny()) + " x " + std::to_string(grid_.nz())
                                    + "): give one value per node of the grid");
    for(int k = 0; k < grid_.nz(); ++k)
      for(int j = 0; j < grid_.ny(); ++j)
        for(int i = 0; i < grid_.nx(); ++i)
          if(!std::isfinite(values_[grid_.index(i, j, k)]))
          {
            std::ostringstream os;
            os << "Sampled_function_3: the value at node (" << i << "," << j << "," << k << "), x = ("
               << grid_.node(i, j, k).transpose() << "), is " << values_[grid_.index(i, j, k)]
               << ": every sample must be finite";
            throw Invalid_parameter_error(os.str());
          }
  }

  const Grid_3& grid() const { return grid_; }
  /// One value per node, indexed by `grid().index(i,j,k)`.
  const std::vector<double>& values() const { return values_; }

  double operator()(const Eigen::Vector3d& x) const
  {
    const Grid_3& grid = grid_;
    const std::vector<double>& values = values_;
    const Eigen::Vector3d c = grid.to_index(x);
    const int i = std::clamp(int(std::floor(c.x())), 0, grid.nx() - 2);
    const int j = std::clamp(int(std::floor(c.y())), 0, grid.ny() - 2);
    const int k = std::clamp(int(std::floor(c.z())), 0, grid.nz() - 2);
    const double s = c.x() - i, t = c.y() - j, r = c.z() - k;
    double sum = 0.;
    for(int corner = 0; corner < 8; ++corner)
    {
      const int a = corner & 1, b = (corner >> 1) & 1, e = (corner >> 2) & 1;
      sum += (a ? s : 1 - s) * (b ? t : 1 - t) * (e ? r : 1 - r) * values[grid.index(i + a, j + b, k + e)];
    }
    return sum;
  }

  /// Differentials at node `(i,j,k)` from central differences of the samples (one-sided on the border).
  Implicit_differentials node_differentials(int i, int j, int k) const
  {
    const Grid_3& grid = grid_;
    const std::vector<double>& values = values_;
    const int idx[3] = {i, j, k}, size[3] = {grid.nx(), grid.ny(), grid.nz()};
    auto value = [&](int di, int dj, int dk) {
      return values[grid.index(std::clamp(i + di, 0, grid.nx() - 1), std::clamp(j + dj, 0, grid.ny() - 1),
                               std::clamp(k + dk, 0, grid.nz() - 1))];
    };
    auto shifted = [&](int axis, int step, int axis2 = -1, int step2 = 0) {
      int o[3] = {0, 0, 0};
      o[axis] += step;
      if(axis2 >= 0) o[axis2] += step2;
      return value(o[0], o[1], o[2]);
    };
    Eigen::Vector3d gradient;
    Eigen::Matrix3d hessian;
    const double h = grid.h();
    for(int a = 0; a < 3; ++a)
    {
      // Keep the stencil inside the grid: shift the centre of the difference on the border.
      const int c = std::clamp(idx[a], 1, size[a] - 2) - idx[a];
      gradient[a] = (shifted(a, c + 1) - shifted(a, c - 1)) / (2. * h);
      hessian(a, a) = (shifted(a, c + 1) - 2. * shifted(a, c) + shifted(a, c - 1)) / (h * h);
    }
    for(int a = 0; a < 3; ++a)
      for(int b = a + 1; b < 3; ++b)
        hessian(a, b) = hessian(b, a) =
          (shifted(a, 1, b, 1) - shifted(a, 1, b, -1) - shifted(a, -1, b, 1) + shifted(a, -1, b, -1)) / (4. * h * h);
    return implicit_differentials_from(values[grid.index(i, j, k)], gradient, hessian, grid.node(i, j, k));
  }

private:
  Grid_3 grid_;
  std::vector<double> values_;
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_IMPLICIT_SURFACE_METRIC_H
