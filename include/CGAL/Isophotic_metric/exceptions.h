// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Exception types of the Isophotic_metric package.
// Every error raised on bad input derives from CGAL::Isophotic_metric::Error and its message
// names the offending element (face, vertex, edge, parameter or source).
#ifndef CGAL_ISOPHOTIC_METRIC_EXCEPTIONS_H
#define CGAL_ISOPHOTIC_METRIC_EXCEPTIONS_H

#include <stdexcept>
#include <string>

namespace CGAL {
namespace Isophotic_metric {
namespace internal {

// What to do about the defects of scanned meshes, in the refusals they trigger.
constexpr const char* scan_repair_hint =
  "run CGAL::Isophotic_metric::repair_scanned_mesh() on the mesh first, or isophotic --repair on the command line";

} // namespace internal

/// \ingroup PkgIsophoticMetricValidation
/// Base class of every exception thrown by the package.
class Error : public std::runtime_error
{
public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

/// \ingroup PkgIsophoticMetricValidation
/// The mesh cannot be processed: a non-triangle face, a non-manifold or invalid halfedge
/// structure, a NaN/inf coordinate or normal, a zero normal, a (lifted) edge of zero length.
class Invalid_mesh_error : public Error
{
public:
  explicit Invalid_mesh_error(const std::string& what) : Error(what) {}
};

/// \ingroup PkgIsophoticMetricValidation
/// A parameter is out of its domain: a negative or non-finite weight, `w = w' = 0`,
/// a negative radius or distance bound, a fraction outside [0,1], ...
class Invalid_parameter_error : public Error
{
public:
  explicit Invalid_parameter_error(const std::string& what) : Error(what) {}
};

/// \ingroup PkgIsophoticMetricValidation
/// A source (vertex, face, surface point, seed) does not belong to the mesh or is malformed
/// (barycentric coordinates that are negative, non-finite or do not sum to one).
class Invalid_source_error : public Error
{
public:
  explicit Invalid_source_error(const std::string& what) : Error(what) {}
};

/// \ingroup PkgIsophoticMetricValidation
/// A long computation was stopped by its visitor (progress callback returned `false`).
class Cancelled_error : public Error
{
public:
  explicit Cancelled_error(const std::string& what) : Error(what) {}
};

} // namespace Isophotic_metric
} // namespace CGAL

#endif // CGAL_ISOPHOTIC_METRIC_EXCEPTIONS_H
