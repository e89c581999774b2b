// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Least-squares fitting of the fundamental surfaces of CAD (plane, cylinder, cone, sphere, torus) to
// oriented, weighted sample points, with distance and normal queries on the fitted surface.
#ifndef CGAL_ISOPHOTIC_METRIC_SEGMENTATION_FIT_FUNDAMENTAL_SURFACE_H
#define CGAL_ISOPHOTIC_METRIC_SEGMENTATION_FIT_FUNDAMENTAL_SURFACE_H

#include <CGAL/Isophotic_metric/exceptions.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

namespace CGAL {
namespace Isophotic_metric {

/// \ingroup PkgIsophoticMetricSegmentation
/// The type of a fundamental surface. The numbering is that of the `surface_type` property of the
/// generated CAD part suite (data/cad_parts).
enum class Surface_type : unsigned char { plane = 0, cylinder = 1, cone = 2, sphere = 3, torus = 4, free_form = 5 };

/// \ingroup PkgIsophoticMetricSegmentation
/// Name of a surface type ("plane", "cylinder", ...).
inline const char* surface_type_name(Surface_type t)
{
  static const char* names[] = {"plane", "cylinder", "cone", "sphere", "torus", "free-form"};
  return names[static_cast<int>(t)];
}

/// \ingroup PkgIsophoticMetricSegmentation
/// A fitted fundamental surface. Which fields carry meaning depends on `type`:
/// - plane: `center` a point of the plane, `axis` its unit normal (pointing like the sample normals);
/// - cylinder: `center` a point of the axis, `axis` its unit direction, `radius`;
/// - cone: `center` the apex, `axis` the unit direction from the apex into the cone, `half_angle` (radians);
/// - sphere: `center`, `radius`;
/// - torus: `center`, `axis` the unit normal of its spine circle's plane, `radius` the spine radius
///   (major radius), `minor_radius` the tube radius;
/// - free-form: no parameters.
///
/// `outward` is `true` when the sample normals point away from the axis or centre (a convex cylinder or
/// sphere seen from outside the material, a boss; `false` for a hole or a concave fillet). `residual`
/// is the area-weighted root mean square distance of the samples to the surface (infinite when the fit
/// failed).
struct Fundamental_surface
{
  typedef CGAL::Epick::Point_3 Point_3;
  typedef CGAL::Epick::Vector_3 Vector_3;
  Surface_type type = Surface_type::free_form;
  Point_3 center = Point_3(0, 0, 0);
  Vector_3 axis = Vector_3(0, 0, 1);
  double radius = 0, minor_radius = 0, half_angle = 0;
  bool outward = true;
  double residual = std::numeric_limits<double>::infinity();
};

namespace internal {

typedef Eigen::Vector3d Vec3;

// One oriented sample: a point, its unit normal, its weight (an area), and how far it may lie from
// its surface (the segmentation's local distance tolerance; unused by the fits).
struct Surface_sample
{
  Vec3 p, n;
  double w, tolerance = 0;
};

inline Vec3 to_eigen(const CGAL::Epick::Point_3& p) { return Vec3(p.x(), p.y(), p.z()); }
inline Vec3 to_eigen(const CGAL::Epick::Vector_3& v) { return Vec3(v.x(), v.y(), v.z()); }

// The same surface with Eigen vectors: the form every query and fit works on.
struct Surface_model
{
  Surface_type type = Surface_type::free_form;
  Vec3 c = Vec3::Zero(), a = Vec3::UnitZ();
  double radius = 0, minor_radius = 0, half_angle = 0;
  bool outward = true;

  // distance to the surface, and the surface's unit normal at the nearest point, oriented like the samples
  double distance(const Vec3& p) const
  {
    switch(type)
    {
    case Surface_type::plane: return std::abs((p - c).dot(a));
    case Surface_type::sphere: return std::abs((p - c).norm() - radius);
    case Surface_type::cylinder: { const Vec3 d = p - c; return std::abs((d - d.dot(a) * a).norm() - radius); }
    case Surface_type::cone:
    {
      const Vec3 d = p - c;
      const double t = d.dot(a), rho = (d - t * a).norm();
      // beyond the apex the nearest point is the apex itself (the cone is one nappe)
      const double along = rho * std::sin(half_angle) + t * std::cos(half_angle);
      return along < 0 ? d.norm() : std::abs(rho * std::cos(half_angle) - t * std::sin(half_angle));
    }
    case Surface_type::torus:
    {
      const Vec3 d = p - c;
      const double t = d.dot(a), rho = (d - t * a).norm();
      return std::abs(std::sqrt((rho - radius) * (rho - radius) + t * t) - minor_radius);
    }
    default: return std::numeric_limits<double>::infinity();
    }
  }

  Vec3 normal(const Vec3& p) const
  {
    Vec3 g = a; // away from the axis or centre
    const Vec3 d = p - c;
    const double t = d.dot(a);
    Vec3 radial = d - t * a;
    radial = radial.norm() > 0 ? Vec3(radial.normalized()) : Vec3(a.unitOrthogonal());
    switch(type)
    {
    case Surface_type::plane: return a;
    case Surface_type::sphere: g = d.norm() > 0 ? Vec3(d.normalized()) : a; break;
    case Surface_type::cylinder: g = radial; break;
    case Surface_type::cone: g = std::cos(half_angle) * radial - std::sin(half_angle) * a; break;
    case Surface_type::torus:
    {
      const Vec3 from_spine = d - radius * radial;
      g = from_spine.norm() > 0 ? Vec3(from_spine.normalized()) : radial;
      break;
    }
    default: return a;
    }
    return outward ? g : Vec3(-g);
  }
};

inline double sum_of_weights(const std::vector<Surface_sample>& s)
{
  double w = 0;
  for(const Surface_sample& x : s)
    w += x.w;
  return w;
}

// weighted mean of a function of the samples
template <class F>
auto weighted_mean(const std::vector<Surface_sample>& s, F&& f) -> decltype(f(s[0]))
{
  decltype(f(s[0])) m = f(s[0]) * 0.0;
  double w = 0;
  for(const Surface_sample& x : s)
  {
    m += x.w * f(x);
    w += x.w;
  }
  return m / w;
}

inline double rms_distance(const Surface_model& m, const std::vector<Surface_sample>& s)
{
  double e = 0, w = 0;
  for(const Surface_sample& x : s)
  {
    const double d = m.distance(x.p);
    e += x.w * d * d;
    w += x.w;
  }
  return w > 0 ? std::sqrt(e / w) : std::numeric_limits<double>::infinity();
}

// eigenvector of the smallest eigenvalue of a symmetric 3x3 matrix, and that eigenvalue over the largest
inline Vec3 smallest_eigenvector(const Eigen::Matrix3d& m, double* ratio = nullptr)
{
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(m);
  if(ratio)
    *ratio = solver.eigenvalues()(2) > 0 ? solver.eigenvalues()(0) / solver.eigenvalues()(2) : 0;
  return solver.eigenvectors().col(0);
}

// orients `m` (outward flag) to agree with the sample normals on average
inline void orient_like_samples(Surface_model& m, const std::vector<Surface_sample>& s)
{
  m.outward = true;
  double agreement = 0;
  for(const Surface_sample& x : s)
    agreement += x.w * x.n.dot(m.normal(x.p));
  m.outward = agreement >= 0;
}

inline Surface_model fit_plane(const std::vector<Surface_sample>& s)
{
  Surface_model m;
  m.type = Surface_type::plane;
  m.c = weighted_mean(s, [](const Surface_sample& x) -> Vec3 { return x.p; });
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for(const Surface_sample& x : s)
    cov += x.w * (x.p - m.c) * (x.p - m.c).transpose();
  m.a = smallest_eigenvector(cov);
  if(m.a.dot(weighted_mean(s, [](const Surface_sample& x) -> Vec3 { return x.n; })) < 0)
    m.a = -m.a;
  return m;
}

// Circle (D = 2) or sphere (D = 3) through points q_i with unit directions u_i from the centre (signed
// radius): least squares of c + r u_i = q_i for the start, then the geometric fit by the fixed-point
// iteration r = mean |q_i - c|, c = mean (q_i - r (q_i - c)/|q_i - c|), which decreases the squared
// distances.
template <int D>
void fit_round(const std::vector<Eigen::Matrix<double, D, 1>>& q, const std::vector<Eigen::Matrix<double, D, 1>>& u,
               const std::vector<double>& w, Eigen::Matrix<double, D, 1>& centre, double& r)
{
  typedef Eigen::Matrix<double, D, 1> V;
  typedef Eigen::Matrix<double, D + 1, 1> Row;
  Eigen::Matrix<double, D + 1, D + 1> A = Eigen::Matrix<double, D + 1, D + 1>::Zero();
  Row b = Row::Zero();
  for(std::size_t i = 0; i < q.size(); ++i)
    for(int k = 0; k < D; ++k)
    {
      Row row = Row::Zero();
      row(k) = 1;
      row(D) = u[i](k);
      A += w[i] * row * row.transpose();
      b += w[i] * row * q[i](k);
    }
  const Row x = A.ldlt().solve(b);
  centre = x.template head<D>();
  double W = 0;
  for(double wi : w)
    W += wi;
  for(int iteration = 0; iteration < 8; ++iteration)
  {
    r = 0;
    for(std::size_t i = 0; i < q.size(); ++i)
      r += w[i] * (q[i] - centre).norm();
    r /= W;
    V next = V::Zero();
    for(std::size_t i = 0; i < q.size(); ++i)
    {
      const V e = q[i] - centre;
      const double len = e.norm();
      next += w[i] * (len > 0 ? V(q[i] - r * e / len) : V(q[i]));
    }
    centre = next / W;
  }
}

inline Surface_model fit_sphere(const std::vector<Surface_sample>& s)
{
  std::vector<Vec3> q, u;
  std::vector<double> w;
  for(const Surface_sample& x : s)
  {
    q.push_back(x.p);
    u.push_back(x.n);
    w.push_back(x.w);
  }
  Vec3 centre;
  Surface_model m;
  m.type = Surface_type::sphere;
  fit_round<3>(q, u, w, centre, m.radius);
  m.c = centre;
  orient_like_samples(m, s);
  return m;
}

// circle fit of the samples projected on the plane normal to `axis`
inline Surface_model fit_cylinder_with_axis(const std::vector<Surface_sample>& s, const Vec3& axis)
{
  Surface_model m;
  m.type = Surface_type::cylinder;
  m.a = axis.normalized();
  const Vec3 e1 = m.a.unitOrthogonal(), e2 = m.a.cross(e1);
  std::vector<Eigen::Vector2d> q, u;
  std::vector<double> w;
  for(const Surface_sample& x : s)
  {
    Eigen::Vector2d n2(x.n.dot(e1), x.n.dot(e2));
    if(n2.norm() > 0)
      n2.normalize();
    q.emplace_back(x.p.dot(e1), x.p.dot(e2));
    u.push_back(n2);
    w.push_back(x.w);
  }
  Eigen::Vector2d centre;
  fit_round<2>(q, u, w, centre, m.radius);
  const double along = weighted_mean(s, [&](const Surface_sample& x) { return x.p.dot(m.a); });
  m.c = centre(0) * e1 + centre(1) * e2 + along * m.a;
  orient_like_samples(m, s);
  return m;
}

// the normals of a cylinder are orthogonal to its axis
inline Surface_model fit_cylinder(const std::vector<Surface_sample>& s)
{
  Eigen::Matrix3d nn = Eigen::Matrix3d::Zero();
  for(const Surface_sample& x : s)
    nn += x.w * x.n * x.n.transpose();
  return fit_cylinder_with_axis(s, smallest_eigenvector(nn));
}

// The normals of a cone make a constant angle with its axis (smallest variance of n.a), and every
// tangent plane passes through the apex (least squares of n_i.(x - p_i) = 0).
inline Surface_model fit_cone(const std::vector<Surface_sample>& s)
{
  Surface_model m;
  m.type = Surface_type::cone;
  const Vec3 mean_normal = weighted_mean(s, [](const Surface_sample& x) -> Vec3 { return x.n; });
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero(), nn = Eigen::Matrix3d::Zero();
  Vec3 rhs = Vec3::Zero();
  for(const Surface_sample& x : s)
  {
    cov += x.w * (x.n - mean_normal) * (x.n - mean_normal).transpose();
    nn += x.w * x.n * x.n.transpose();
    rhs += x.w * x.n * x.n.dot(x.p);
  }
  m.a = smallest_eigenvector(cov);
  double conditioning = 0;
  smallest_eigenvector(nn, &conditioning);
  // normals nearly in one plane: a cylinder (apex at infinity) or a plane, not a cone
  if(conditioning < 1e-3)
    return Surface_model();
  m.c = nn.ldlt().solve(rhs);
  if(weighted_mean(s, [&](const Surface_sample& x) { return (x.p - m.c).dot(m.a); }) < 0)
    m.a = -m.a;
  m.half_angle = weighted_mean(s, [&](const Surface_sample& x) {
    const Vec3 d = x.p - m.c;
    const double t = d.dot(m.a);
    return std::atan2((d - t * m.a).norm(), t);
  });
  orient_like_samples(m, s);
  return m;
}

// every k-th sample, at most `n` of them
inline std::vector<Surface_sample> subsample(const std::vector<Surface_sample>& s, std::size_t n)
{
  if(s.size() <= n)
    return s;
  std::vector<Surface_sample> out;
  const double step = double(s.size()) / n;
  for(std::size_t i = 0; i < n; ++i)
    out.push_back(s[std::size_t(i * step)]);
  return out;
}

// The normal lines of a surface of revolution all meet its axis. A line through p along n meets the
// axis through c along a (unit) when a.(p x n) + (c x a).n = 0: linear in (a, c x a), so the axis is
// the smallest eigenvector of a 6x6 quadratic form, with c x a eliminated (its optimum for each a is
// linear in a) to leave a 3x3 one. Computed about the samples' centroid for conditioning.
inline void fit_axis_of_revolution(const std::vector<Surface_sample>& s, Vec3& point, Vec3& direction)
{
  const Vec3 centroid = weighted_mean(s, [](const Surface_sample& x) -> Vec3 { return x.p; });
  Eigen::Matrix3d mm = Eigen::Matrix3d::Zero(), mn = Eigen::Matrix3d::Zero(), nn = Eigen::Matrix3d::Zero();
  for(const Surface_sample& x : s)
  {
    const Vec3 m = (x.p - centroid).cross(x.n);
    mm += x.w * m * m.transpose();
    mn += x.w * m * x.n.transpose();
    nn += x.w * x.n * x.n.transpose();
  }
  // normals in one plane (a cylinder) leave nn singular: a tiny ridge keeps the solve finite
  nn += 1e-12 * nn.trace() * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d nn_inverse_nm = nn.ldlt().solve(Eigen::Matrix3d(mn.transpose()));
  const Eigen::Matrix3d reduced = mm - mn * nn_inverse_nm;
  direction = smallest_eigenvector(0.5 * (reduced + reduced.transpose()));
  const Vec3 moment = -nn_inverse_nm * direction; // c x a
  point = centroid + direction.cross(moment);     // the axis point nearest to the centroid
}

// Torus from its axis (fit_axis_of_revolution()): in the meridian half-plane (distance rho from the
// axis, height t along it) the points lie on a circle of the tube radius around the spine, each at its
// normal's direction from it: the circle fit of the sphere and cylinder. Closed form, but the axis comes
// from the normals alone, which noise tilts.
inline Surface_model fit_torus_about_axis_of_revolution(const std::vector<Surface_sample>& s)
{
  Surface_model m;
  m.type = Surface_type::torus;
  Vec3 axis_point;
  fit_axis_of_revolution(s, axis_point, m.a);
  std::vector<Eigen::Vector2d> q, u;
  std::vector<double> w;
  for(const Surface_sample& x : s)
  {
    const Vec3 d = x.p - axis_point;
    const double t = d.dot(m.a);
    const Vec3 radial = d - t * m.a;
    const double rho = radial.norm();
    const Vec3 e = rho > 0 ? Vec3(radial / rho) : Vec3(m.a.unitOrthogonal());
    Eigen::Vector2d n2(x.n.dot(e), x.n.dot(m.a));
    if(n2.norm() > 0)
      n2.normalize();
    q.emplace_back(rho, t);
    u.push_back(n2);
    w.push_back(x.w);
  }
  Eigen::Vector2d spine; // (spine radius, height of the spine's plane)
  double tube = 0;
  fit_round<2>(q, u, w, spine, tube);
  // a spine on the far side of the axis describes no torus of this package's form
  if(!(spine(0) >= 0) || !std::isfinite(tube))
    return Surface_model();
  m.c = axis_point + spine(1) * m.a;
  m.radius = spine(0);
  m.minor_radius = std::abs(tube);
  orient_like_samples(m, s);
  return m;
}

// Torus of signed tube radius r: the points q_i = p_i - r n_i lie on the spine circle; fit its plane
// (least squares) and the circle in it.
inline Surface_model fit_torus_with_tube(const std::vector<Surface_sample>& s, double r)
{
  Surface_model m;
  m.type = Surface_type::torus;
  std::vector<Surface_sample> spine(s);
  for(Surface_sample& x : spine)
    x.p -= r * x.n;
  const Surface_model plane = fit_plane(spine);
  m.a = plane.a;
  const Vec3 e1 = m.a.unitOrthogonal(), e2 = m.a.cross(e1);
  // algebraic circle fit: |q|^2 = 2 c.q + k, linear in (c, k)
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Vec3 b = Vec3::Zero();
  for(const Surface_sample& x : spine)
  {
    const Vec3 d = x.p - plane.c;
    const Vec3 row(2 * d.dot(e1), 2 * d.dot(e2), 1);
    A += x.w * row * row.transpose();
    b += x.w * row * (d.dot(e1) * d.dot(e1) + d.dot(e2) * d.dot(e2));
  }
  const Vec3 x = A.ldlt().solve(b);
  m.c = plane.c + x(0) * e1 + x(1) * e2;
  m.radius = std::sqrt(std::max(0.0, x(2) + x(0) * x(0) + x(1) * x(1)));
  m.minor_radius = std::abs(r);
  orient_like_samples(m, s);
  return m;
}

// The torus of the closed form (fit_torus_about_axis_of_revolution()), then the signed tube radius
// that minimises the residual of fit_torus_with_tube() (which takes the axis from the spine points,
// less sensitive to noisy normals), by golden-section search within a factor 1.5 of the closed
// form's; the better of the two.
inline Surface_model fit_torus(const std::vector<Surface_sample>& s)
{
  const std::vector<Surface_sample> few = subsample(s, 400);
  const Surface_model closed = fit_torus_about_axis_of_revolution(few);
  if(closed.type != Surface_type::torus || !(closed.minor_radius > 0))
    return closed;
  // the tube's signed radius: positive when the normals point away from the spine
  const Vec3 d = few[0].p - closed.c;
  const Vec3 radial = d - d.dot(closed.a) * closed.a;
  const Vec3 from_spine = d - closed.radius * (radial.norm() > 0 ? Vec3(radial.normalized()) : Vec3(closed.a.unitOrthogonal()));
  const double r0 = from_spine.dot(few[0].n) >= 0 ? closed.minor_radius : -closed.minor_radius;
  auto cost = [&](double r) { return rms_distance(fit_torus_with_tube(few, r), few); };
  double a = r0 / 1.5, b = r0 * 1.5;
  const double golden = 0.5 * (std::sqrt(5.0) - 1);
  double x1 = b - golden * (b - a), x2 = a + golden * (b - a), f1 = cost(x1), f2 = cost(x2);
  for(int i = 0; i < 14; ++i) // brackets the tube radius to 0.3 %
  {
    if(f1 < f2)
    {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - golden * (b - a);
      f1 = cost(x1);
    }
    else
    {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + golden * (b - a);
      f2 = cost(x2);
    }
  }
  const Surface_model searched = fit_torus_with_tube(s, f1 < f2 ? x1 : x2);
  return rms_distance(searched, s) < rms_distance(closed, s) ? searched : closed;
}

// Fits on at most `max_fit_samples` samples, evenly taken: the parameters of a large set are settled
// long before that, and the cost of a fit stays bounded.
constexpr std::size_t max_fit_samples = 2000;

inline Surface_model fit_model(Surface_type type, const std::vector<Surface_sample>& all)
{
  if(all.size() < 3 || !(sum_of_weights(all) > 0))
    return Surface_model();
  const std::vector<Surface_sample> few = subsample(all, max_fit_samples);
  const std::vector<Surface_sample>& s = all.size() > max_fit_samples ? few : all;
  switch(type)
  {
  case Surface_type::plane: return fit_plane(s);
  case Surface_type::cylinder: return fit_cylinder(s);
  case Surface_type::cone: return fit_cone(s);
  case Surface_type::sphere: return fit_sphere(s);
  case Surface_type::torus: return fit_torus(s);
  default: return Surface_model();
  }
}

inline Fundamental_surface to_fundamental_surface(const Surface_model& m, double residual)
{
  Fundamental_surface f;
  f.type = m.type;
  f.center = Fundamental_surface::Point_3(m.c(0), m.c(1), m.c(2));
  f.axis = Fundamental_surface::Vector_3(m.a(0), m.a(1), m.a(2));
  f.radius = m.radius;
  f.minor_radius = m.minor_radius;
  f.half_angle = m.half_angle;
  f.outward = m.outward;
  f.residual = m.type == Surface_type::free_form ? std::numeric_limits<double>::infinity() : residual;
  return f;
}

inline Surface_model to_model(const Fundamental_surface& f)
{
  Surface_model m;
  m.type = f.type;
  m.c = to_eigen(f.center);
  m.a = to_eigen(f.axis);
  if(m.a.norm() > 0)
    m.a.normalize();
  m.radius = f.radius;
  m.minor_radius = f.minor_radius;
  m.half_angle = f.half_angle;
  m.outward = f.outward;
  return m;
}

} // namespace internal

/// \ingroup PkgIsophoticMetricSegmentation
///
/// \brief fits a fundamental surface of the given type to oriented sample points by least squares.
///
/// - plane: through the weighted centroid, normal to the direction of least spread;
/// - sphere: centre and radius from \f$ c + r\,n_i \approx p_i \f$ (points along their normals meet at
///   the centre), then refined to the geometric least-squares sphere;
/// - cylinder: the axis is the direction most orthogonal to all normals (least eigenvector of
///   \f$ \sum w_i n_i n_i^T \f$), then the circle of the points projected along it as for the sphere;
/// - cone: the axis is the direction of least spread of the normals (they make a constant angle with
///   it), the apex the point nearest to every tangent plane, the half angle the mean angle of the points
///   seen from the apex; normals that lie in one plane (a cylinder or a plane) give no cone;
/// - torus: the axis is the line that the normal lines \f$ p_i + t\,n_i \f$ meet best (a linear
///   condition on the axis' Plücker coordinates: the least eigenvector of a 3x3 matrix), then, in the
///   half-plane of the distance from the axis and the height along it, the circle of the tube around
///   the spine as for the sphere (closed form); then the tube radius is refined within a factor 1.5:
///   for a tube radius \f$ r \f$ (signed), the points \f$ p_i - r\,n_i \f$ lie on the spine circle,
///   fitted by a plane and a circle in it, and \f$ r \f$ minimises the residual (golden-section
///   search); the better of the two.
///
/// Exact samples of a surface give its parameters to rounding. The normals must be unit vectors, all
/// pointing to the same side of the surface.
///
/// \tparam PointRange a range of `CGAL::Epick::Point_3`
/// \tparam NormalRange a range of `CGAL::Epick::Vector_3` (unit normals)
/// \tparam WeightRange a range of non-negative `double` (e.g. face areas)
/// \returns the fitted surface with its residual (RMS distance), or a free-form surface with an infinite
///   residual when the type cannot be fitted (fewer than 3 samples, zero total weight, no cone)
/// \throws Invalid_parameter_error when the ranges differ in size or `type` is `Surface_type::free_form`
template <class PointRange, class NormalRange, class WeightRange>
Fundamental_surface fit_fundamental_surface(Surface_type type, const PointRange& points, const NormalRange& normals,
                                            const WeightRange& weights)
{
  if(type == Surface_type::free_form)
    throw Invalid_parameter_error("fit_fundamental_surface: a free-form surface has no parameters to fit; "
                                  "ask for a plane, cylinder, cone, sphere or torus");
  std::vector<internal::Surface_sample> s;
  auto n = std::begin(normals);
  auto w = std::begin(weights);
  for(auto p = std::begin(points); p != std::end(points); ++p, ++n, ++w)
  {
    if(n == std::end(normals) || w == std::end(weights))
      throw Invalid_parameter_error("fit_fundamental_surface: fewer normals or weights than points (sample " +
                                    std::to_string(s.size()) + ")");
    s.push_back({internal::to_eigen(*p), internal::to_eigen(*n), double(*w), 0.0});
  }
  if(n != std::end(normals) || w != std::end(weights))
    throw Invalid_parameter_error("fit_fundamental_surface: more normals or weights than points (" +
                                  std::to_string(s.size()) + " points)");
  const internal::Surface_model m = internal::fit_model(type, s);
  return internal::to_fundamental_surface(m, internal::rms_distance(m, s));
}

/// \ingroup PkgIsophoticMetricSegmentation
/// Distance from `p` to the surface `s` (infinite for a free-form surface).
inline double distance_to_surface(const Fundamental_surface& s, const CGAL::Epick::Point_3& p)
{
  return internal::to_model(s).distance(internal::to_eigen(p));
}

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_SEGMENTATION_FIT_FUNDAMENTAL_SURFACE_H
