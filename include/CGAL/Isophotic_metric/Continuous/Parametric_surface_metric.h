// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Isophotic metric of a parametric surface x(u,v):  M = w I + w' III  (Pottmann et al. 2004, Sect. 2.1).
#ifndef CGAL_ISOPHOTIC_METRIC_CONTINUOUS_PARAMETRIC_SURFACE_METRIC_H
#define CGAL_ISOPHOTIC_METRIC_CONTINUOUS_PARAMETRIC_SURFACE_METRIC_H

#include <CGAL/Isophotic_metric/exceptions.h>

#include <Eigen/Dense>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricContinuousRef
/// First and second order differential quantities of a parametric surface at one parameter point.
struct Surface_differentials
{
  Eigen::Vector3d point, xu, xv;   ///< x and its first partial derivatives
  Eigen::Vector3d normal;          ///< unit normal n = x_u x x_v / |x_u x x_v|
  Eigen::Vector3d nu, nv;          ///< partial derivatives of the unit normal
  Eigen::Matrix2d first_fundamental_form;  ///< I   = [x_u.x_u, x_u.x_v; x_u.x_v, x_v.x_v]
  Eigen::Matrix2d third_fundamental_form;  ///< III = [n_u.n_u, n_u.n_v; n_u.n_v, n_v.n_v]
};

namespace internal {

template <typename S, typename = void>
struct has_partial_derivatives : std::false_type {};
template <typename S>
struct has_partial_derivatives<S, std::void_t<decltype(std::declval<const S&>().partial_derivatives(
  0., 0., std::declval<Eigen::Vector3d&>(), std::declval<Eigen::Vector3d&>()))>> : std::true_type {};

template <typename S, typename = void>
struct has_second_partial_derivatives : std::false_type {};
template <typename S>
struct has_second_partial_derivatives<S, std::void_t<decltype(std::declval<const S&>().second_partial_derivatives(
  0., 0., std::declval<Eigen::Vector3d&>(), std::declval<Eigen::Vector3d&>(), std::declval<Eigen::Vector3d&>()))>>
  : std::true_type {};

// Finite-difference steps, relative to the magnitude of the parameter: balance truncation
// (h^2) against round-off (eps/h for first, eps/h^2 for second derivatives).
inline double fd_step_first(double t) { return 6e-6 * (1. + std::abs(t)); }
inline double fd_step_second(double t) { return 1.2e-4 * (1. + std::abs(t)); }

template <typename Surface>
void first_derivatives(const Surface& s, double u, double v, Eigen::Vector3d& xu, Eigen::Vector3d& xv)
{
  if constexpr(has_partial_derivatives<Surface>::value)
    s.partial_derivatives(u, v, xu, xv);
  else
  {
    const double hu = fd_step_first(u), hv = fd_step_first(v);
    xu = (s.point(u + hu, v) - s.point(u - hu, v)) / (2. * hu);
    xv = (s.point(u, v + hv) - s.point(u, v - hv)) / (2. * hv);
  }
}

template <typename Surface>
void second_derivatives(const Surface& s, double u, double v,
                        Eigen::Vector3d& xuu, Eigen::Vector3d& xuv, Eigen::Vector3d& xvv)
{
  if constexpr(has_second_partial_derivatives<Surface>::value)
    s.second_partial_derivatives(u, v, xuu, xuv, xvv);
  else if constexpr(has_partial_derivatives<Surface>::value)
  {
    const double hu = fd_step_first(u), hv = fd_step_first(v);
    Eigen::Vector3d a_u, a_v, b_u, b_v;
    s.partial_derivatives(u + hu, v, a_u, a_v);
    s.partial_derivatives(u - hu, v, b_u, b_v);
    xuu = (a_u - b_u) / (2. * hu);
    const Eigen::Vector3d xvu = (a_v - b_v) / (2. * hu);
    s.partial_derivatives(u, v + hv, a_u, a_v);
    s.partial_derivatives(u, v - hv, b_u, b_v);
    xvv = (a_v - b_v) / (2. * hv);
    xuv = 0.5 * (xvu + (a_u - b_u) / (2. * hv));
  }
  else
  {
    const double hu = fd_step_second(u), hv = fd_step_second(v);
    const Eigen::Vector3d x = s.point(u, v);
    xuu = (s.point(u + hu, v) - 2. * x + s.point(u - hu, v)) / (hu * hu);
    xvv = (s.point(u, v + hv) - 2. * x + s.point(u, v - hv)) / (hv * hv);
    xuv = (s.point(u + hu, v + hv) - s.point(u + hu, v - hv) - s.point(u - hu, v + hv)
           + s.point(u - hu, v - hv)) / (4. * hu * hv);
  }
}

} // namespace internal

/// \ingroup PkgIsophoticMetricContinuousRef
/// Computes point, unit normal, its derivatives, and the first and third fundamental forms of
/// `surface` at `(u,v)`.  Uses the surface's own derivatives when it provides them
/// (see `ParametricSurface`), central finite differences otherwise.
/// \throws Invalid_parameter_error if `(u,v)` is not finite, or the surface is singular there
///         (`x_u x x_v = 0`) or returns non-finite values
template <typename ParametricSurface>
Surface_differentials surface_differentials(const ParametricSurface& surface, double u, double v)
{
  auto fail = [&](const std::string& why) {
    std::ostringstream os;
    os << "surface_differentials: " << why << " at (u,v) = (" << u << ", " << v << ")";
    throw Invalid_parameter_error(os.str());
  };
  if(!std::isfinite(u) || !std::isfinite(v)) fail("non-finite parameter");
  Surface_differentials sd;
  sd.point = surface.point(u, v);
  internal::first_derivatives(surface, u, v, sd.xu, sd.xv);
  Eigen::Vector3d xuu, xuv, xvv;
  internal::second_derivatives(surface, u, v, xuu, xuv, xvv);
  if(!sd.point.allFinite() || !sd.xu.allFinite() || !sd.xv.allFinite()
     || !xuu.allFinite() || !xuv.allFinite() || !xvv.allFinite())
    fail("non-finite point or derivative");

  const Eigen::Vector3d m = sd.xu.cross(sd.xv);
  const double m_norm = m.norm();
  if(!(m_norm > 1e-10 * std::max(sd.xu.squaredNorm(), sd.xv.squaredNorm())))
    fail("singular parametrisation (x_u and x_v are parallel)");
  sd.normal = m / m_norm;
  // Derivative of m/|m|: the part of m' orthogonal to n, divided by |m|.
  const Eigen::Vector3d mu = xuu.cross(sd.xv) + sd.xu.cross(xuv);
  const Eigen::Vector3d mv = xuv.cross(sd.xv) + sd.xu.cross(xvv);
  sd.nu = (mu - sd.normal * sd.normal.dot(mu)) / m_norm;
  sd.nv = (mv - sd.normal * sd.normal.dot(mv)) / m_norm;

  sd.first_fundamental_form << sd.xu.dot(sd.xu), sd.xu.dot(sd.xv), sd.xu.dot(sd.xv), sd.xv.dot(sd.xv);
  sd.third_fundamental_form << sd.nu.dot(sd.nu), sd.nu.dot(sd.nv), sd.nu.dot(sd.nv), sd.nv.dot(sd.nv);
  return sd;
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// First fundamental form `I` of `surface` at `(u,v)`.
template <typename ParametricSurface>
Eigen::Matrix2d first_fundamental_form(const ParametricSurface& surface, double u, double v)
{ return surface_differentials(surface, u, v).first_fundamental_form; }

/// \ingroup PkgIsophoticMetricContinuousRef
/// Unit normal `n = x_u x x_v / |x_u x x_v|` of `surface` at `(u,v)`.
template <typename ParametricSurface>
Eigen::Vector3d unit_normal(const ParametricSurface& surface, double u, double v)
{ return surface_differentials(surface, u, v).normal; }

/// \ingroup PkgIsophoticMetricContinuousRef
/// Third fundamental form `III` (first fundamental form of the Gaussian image) at `(u,v)`.
/// It is singular where the Gaussian curvature vanishes.
template <typename ParametricSurface>
Eigen::Matrix2d third_fundamental_form(const ParametricSurface& surface, double u, double v)
{ return surface_differentials(surface, u, v).third_fundamental_form; }

/// \ingroup PkgIsophoticMetricContinuousRef
/// Checks the weights of the regularised isophotic metric `w ds^2 + w' ds*^2`.
/// \throws Invalid_parameter_error unless `w >= 0`, `w' >= 0` are finite and not both zero
inline void check_isophotic_weights(double w, double w_prime)
{
  if(!std::isfinite(w) || w < 0.)
    throw Invalid_parameter_error("euclidean_weight w = " + std::to_string(w) + " must be finite and >= 0");
  if(!std::isfinite(w_prime) || w_prime < 0.)
    throw Invalid_parameter_error("isophotic_weight w' = " + std::to_string(w_prime) + " must be finite and >= 0");
  if(w == 0. && w_prime == 0.)
    throw Invalid_parameter_error("euclidean_weight and isophotic_weight are both zero");
}

/// \ingroup PkgIsophoticMetricContinuousRef
/// The regularised isophotic metric tensor `M = w I + w' III` of `surface` at `(u,v)`
/// (in parameter coordinates).  With `w > 0` it is positive definite everywhere; with `w = 0`
/// it degenerates where the Gaussian curvature vanishes.
/// \throws Invalid_parameter_error on invalid weights (see `check_isophotic_weights()`)
template <typename ParametricSurface>
Eigen::Matrix2d isophotic_metric_tensor(const ParametricSurface& surface, double u, double v,
                                        double w, double w_prime)
{
  check_isophotic_weights(w, w_prime);
  const Surface_differentials sd = surface_differentials(surface, u, v);
  return w * sd.first_fundamental_form + w_prime * sd.third_fundamental_form;
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_CONTINUOUS_PARAMETRIC_SURFACE_METRIC_H
