// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Shared by the translation units of the Python module isophotic_metric: the mesh type, numpy
// conversions with checks that name the offending argument, the metric keyword arguments and the
// interruptible, GIL-free execution of long calls.
#ifndef ISOPHOTIC_METRIC_PYTHON_MODULE_H
#define ISOPHOTIC_METRIC_PYTHON_MODULE_H

#include <functional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/Metric_mesh.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Surface_mesh.h>

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace py = pybind11;
namespace IM = CGAL::Isophotic_metric;

namespace isophotic_metric_python {

typedef CGAL::Exact_predicates_inexact_constructions_kernel Kernel;
typedef CGAL::Surface_mesh<Kernel::Point_3> Mesh;
typedef Mesh::Vertex_index Vertex;
typedef Mesh::Face_index Face;

// Meshes are built from arrays or read from files without removals, so the i-th vertex (face) of
// the arrays is Surface_mesh index i: positions in numpy arrays and descriptors coincide.
typedef py::array_t<double, py::array::c_style | py::array::forcecast> Double_array;
typedef py::array_t<std::int64_t, py::array::c_style | py::array::forcecast> Index_array;

// ------------------------------------------------------------------ numpy in and out

// Barycentric coordinates in Python follow the rows of Mesh.faces, the vertices around the face
// from target(halfedge(f)); in C++ they start at source(halfedge(f)), the last of the row.
inline std::array<double, 3> to_cpp_barycentric(double b0, double b1, double b2) { return {{b2, b0, b1}}; }
inline std::array<double, 3> to_python_barycentric(const std::array<double, 3>& b) { return {{b[1], b[2], b[0]}}; }

/// A C-contiguous float64 view of `a` (no copy when it already is one) of shape (rows, columns);
/// rows = -1 accepts any number of rows, columns = 0 asks for a 1-D array.
Double_array as_doubles(const py::handle& a, const char* name, py::ssize_t rows, py::ssize_t columns);

/// Integer indices (a scalar or a 1-D array) checked against [0, size); `kind` names them in errors
/// ("vertex", "face"). A bool array of length `size` is read as a mask when `accept_mask`.
std::vector<std::uint32_t> as_indices(const py::handle& a, const char* name, const char* kind, std::size_t size,
                                      bool accept_mask = false);

/// A new float64 array of the given shape; the caller fills it.
inline py::array_t<double> new_doubles(std::vector<py::ssize_t> shape) { return py::array_t<double>(shape); }

/// Hands a vector over to numpy without copying it: the array owns the vector through a capsule.
template <class T>
py::array_t<T> to_array(std::vector<T>&& v, std::vector<py::ssize_t> shape)
{
  auto* owner = new std::vector<T>(std::move(v));
  py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owner->data(), free_when_done);
}

// ------------------------------------------------------------------ the metric and the prepared mesh

typedef IM::Metric_mesh<Mesh> Prepared_mesh;

/// The metric keyword arguments common to every call on a mesh, as given from Python; None is
/// "not given" (the C++ default).
struct Metric_arguments
{
  py::object euclidean_weight;    // a number or a per-vertex array
  py::object isophotic_weight;    // a number or a per-vertex array
  py::object weight_length_scale; // a number
  py::object normals;             // an (n, 3) array

  bool any_given() const
  {
    return !euclidean_weight.is_none() || !isophotic_weight.is_none() || !weight_length_scale.is_none() ||
           !normals.is_none();
  }
};

/// The mesh a call is given: a Mesh, or a Metric_mesh (whose mesh it returns).
const Mesh& mesh_of(const py::handle& mesh);

/// The prepared mesh a call runs on: the Metric_mesh given, or one prepared (without the GIL) from
/// the Mesh given and the metric arguments. Throws ValueError for metric arguments with a Metric_mesh.
Prepared_mesh prepared_mesh(const py::handle& mesh, const Metric_arguments& metric);

// Keyword arguments of the metric, in the order of the C++ named parameters.
#define ISOPHOTIC_METRIC_PY_METRIC_ARGS                                                          \
  py::arg("euclidean_weight") = py::none(), py::arg("isophotic_weight") = py::none(),            \
  py::arg("weight_length_scale") = py::none(), py::arg("normals") = py::none()

#define ISOPHOTIC_METRIC_PY_METRIC_DOC                                                           \
  "mesh: a Mesh, or a Metric_mesh prepared once for its metric (then give no metric argument).\n" \
  "euclidean_weight: w, a number or an array of one weight per vertex (default 1).\n"            \
  "isophotic_weight: w', a number or an array of one weight per vertex (default 1);\n"          \
  "    0 gives the Euclidean geodesic metric scaled by sqrt(w).\n"                               \
  "weight_length_scale: L, the length that makes the weights dimensionless (default: the\n"     \
  "    package's default; see suggested_weight_length_scale()).\n"                               \
  "normals: optional (n, 3) array of vertex normals (default: computed, exact on spheres).\n"

// ------------------------------------------------------------------ long calls

/// The cancellation hook of long calls: the propagation's visitor and the `callback` named parameter.
typedef std::function<bool(double)> Callback;

/// Runs `work(callback)` without the GIL. `callback` (a `std::function<bool(double)>` for the
/// propagation's visitor or the `callback` named parameter) takes the GIL back now and then to let
/// Python handle signals: Ctrl-C cancels the computation and the KeyboardInterrupt reaches the
/// caller. `progress`, when not None, is called with the callback's argument (front distance of a
/// propagation) and cancels the computation by returning False (CancelledError).
template <class Work>
void run_interruptible(Work&& work, const py::object& progress = py::none())
{
  bool interrupted = false;
  const std::function<bool(double)> callback = [&](double front) -> bool {
    py::gil_scoped_acquire acquire;
    if(PyErr_CheckSignals() != 0) // a signal handler raised (KeyboardInterrupt): keep its error
    {
      interrupted = true;
      return false;
    }
    return progress.is_none() || py::cast<bool>(progress(front)); // its exceptions propagate
  };
  try
  {
    py::gil_scoped_release release;
    work(callback);
  }
  catch(const IM::Cancelled_error&)
  {
    if(interrupted)
      throw py::error_already_set();
    throw;
  }
}

// ------------------------------------------------------------------ registration

void bind_mesh_and_metric(py::module_& m);
void bind_geodesics(py::module_& m);
void bind_morphology(py::module_& m);
void bind_segmentation(py::module_& m);

} // namespace isophotic_metric_python

#endif // ISOPHOTIC_METRIC_PYTHON_MODULE_H
