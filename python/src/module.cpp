// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// The Python module isophotic_metric: the mesh from numpy arrays or a file, the package's exceptions
// as Python exceptions, the lift and isophotic lengths. Geodesics and morphology are bound in their
// own translation units (geodesics.cpp, morphology.cpp), compiled in parallel.
#include "module.h"

#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_2.h>
#include <CGAL/Isophotic_metric/Continuous/Fast_sweeping_3.h>
#include <CGAL/Isophotic_metric/estimate_vertex_normals.h>
#include <CGAL/Isophotic_metric/isophotic_length.h>
#include <CGAL/Isophotic_metric/suggested_normal_smoothing_scale.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace isophotic_metric_python {

namespace {

std::string shape_of(const py::array& a)
{
  std::ostringstream s;
  s << "(";
  for(py::ssize_t i = 0; i < a.ndim(); ++i)
    s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

} // namespace

Double_array as_doubles(const py::handle& a, const char* name, py::ssize_t rows, py::ssize_t columns)
{
  const py::array raw = py::array::ensure(a);
  if(!raw)
    throw py::type_error(std::string(name) + " must be an array of numbers");
  if(raw.dtype().kind() != 'f' && raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u')
    throw py::type_error(std::string(name) + " must be an array of numbers (got dtype " +
                         std::string(py::str(raw.dtype())) + ")");
  const bool shape_ok = columns == 0 ? raw.ndim() == 1 && (rows < 0 || raw.shape(0) == rows)
                                     : raw.ndim() == 2 && raw.shape(1) == columns && (rows < 0 || raw.shape(0) == rows);
  if(!shape_ok)
  {
    std::string expected = "(" + (rows < 0 ? std::string("n") : std::to_string(rows)) +
                           (columns == 0 ? ",)" : ", " + std::to_string(columns) + ")");
    throw py::value_error(std::string(name) + " must have shape " + expected + " (got " + shape_of(raw) + ")");
  }
  return Double_array::ensure(raw); // a view when already C-contiguous float64
}

std::vector<std::uint32_t> as_indices(const py::handle& a, const char* name, const char* kind, std::size_t size,
                                      bool accept_mask)
{
  const py::array raw = py::array::ensure(a);
  if(!raw || raw.ndim() > 1)
    throw py::type_error(std::string(name) + " must be an index or a 1-D array of indices");
  std::vector<std::uint32_t> result;
  if(raw.dtype().kind() == 'b')
  {
    if(!accept_mask)
      throw py::type_error(std::string(name) + " must hold integer indices, not booleans");
    if(raw.ndim() != 1 || std::size_t(raw.shape(0)) != size)
      throw py::value_error(std::string(name) + " as a boolean mask must have one entry per " + kind + " (" +
                            std::to_string(size) + "), got shape " + shape_of(raw));
    const auto mask = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(raw);
    for(std::size_t i = 0; i < size; ++i)
      if(mask.data()[i])
        result.push_back(std::uint32_t(i));
    return result;
  }
  if(raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u')
    throw py::type_error(std::string(name) + " must hold integer indices (got dtype " +
                         std::string(py::str(raw.dtype())) + ")");
  const Index_array indices = Index_array::ensure(raw);
  result.reserve(std::size_t(indices.size()));
  for(py::ssize_t i = 0; i < indices.size(); ++i)
  {
    const std::int64_t k = indices.data()[i];
    if(k < 0 || std::uint64_t(k) >= size)
      throw IM::Invalid_source_error(std::string(name) + (raw.ndim() ? "[" + std::to_string(i) + "]" : std::string()) +
                                     " = " + std::to_string(k) + " is not a " + kind + " of the mesh (it has " +
                                     std::to_string(size) + (std::string(kind) == "vertex" ? " vertices)" : " faces)"));
    result.push_back(std::uint32_t(k));
  }
  return result;
}

namespace {

// A per-vertex number read from a float64 array; stride 0 gives the same number everywhere.
struct Vertex_value_map
{
  typedef Vertex key_type;
  typedef double value_type;
  typedef double reference;
  typedef boost::readable_property_map_tag category;
  const double* values;
  std::size_t stride;
  friend double get(const Vertex_value_map& m, Vertex v) { return m.values[m.stride * std::size_t(v)]; }
};

// Vertex normals read from an (n, 3) float64 array.
struct Vertex_normal_map
{
  typedef Vertex key_type;
  typedef Kernel::Vector_3 value_type;
  typedef Kernel::Vector_3 reference;
  typedef boost::readable_property_map_tag category;
  const double* xyz;
  friend Kernel::Vector_3 get(const Vertex_normal_map& m, Vertex v)
  {
    const double* n = m.xyz + 3 * std::size_t(v);
    return Kernel::Vector_3(n[0], n[1], n[2]);
  }
};

// Reads the lift from a vector indexed like the vertices.
struct Lifted_point_map
{
  typedef Vertex key_type;
  typedef IM::Lifted_point value_type;
  typedef const IM::Lifted_point& reference;
  typedef boost::readable_property_map_tag category;
  const IM::Lifted_point* points;
  friend reference get(const Lifted_point_map& m, Vertex v) { return m.points[std::size_t(v)]; }
};

// Writes unit normals into a vector of three doubles per vertex.
struct Vertex_normal_writer
{
  typedef Vertex key_type;
  typedef Kernel::Vector_3 value_type;
  typedef value_type reference;
  typedef boost::writable_property_map_tag category;
  double* normals;
  friend void put(const Vertex_normal_writer& m, Vertex v, const Kernel::Vector_3& n)
  {
    double* out = m.normals + 3 * std::size_t(v);
    out[0] = n.x();
    out[1] = n.y();
    out[2] = n.z();
  }
};

// Writes the lift into a vector indexed like the vertices.
struct Lifted_point_writer
{
  typedef Vertex key_type;
  typedef IM::Lifted_point value_type;
  typedef IM::Lifted_point& reference;
  typedef boost::writable_property_map_tag category;
  IM::Lifted_point* points;
  friend void put(const Lifted_point_writer& m, Vertex v, const IM::Lifted_point& x) { m.points[std::size_t(v)] = x; }
};

// A weight argument: a number, or an array with one value per vertex.
struct Weight
{
  bool per_vertex = false;
  double value = 0.;
  Double_array values;

  Weight(const py::object& w, const char* name, std::size_t n)
  {
    const py::array a = py::array::ensure(w);
    if(w.is_none())
      value = 1.; // the C++ default
    else if(a && a.ndim() == 0)
      value = py::cast<double>(w);
    else
    {
      per_vertex = true;
      values = as_doubles(w, name, py::ssize_t(n), 0);
    }
  }
  Vertex_value_map map() const { return per_vertex ? Vertex_value_map{values.data(), 1} : Vertex_value_map{&value, 0}; }
};

// Calls compute_lifted_embedding() with the weights as numbers or maps, the normals and the length
// scale when given (each combination is one instantiation, all of them in this translation unit).
// Its lifting part only: a Mesh is validated when it is built and cannot be modified from Python.
template <class WeightParameters>
void lift_with(const Mesh& mesh, const WeightParameters& weights, const Metric_arguments& a, Lifted_point_writer out)
{
  const bool has_scale = !a.weight_length_scale.is_none();
  const double scale = has_scale ? py::cast<double>(a.weight_length_scale) : 1.;
  auto with_normals = [&](const auto& np) {
    if(a.normals.is_none())
    {
      py::gil_scoped_release release;
      IM::internal::lift_validated_mesh(mesh, out, np);
      return;
    }
    const Double_array normals = as_doubles(a.normals, "normals", py::ssize_t(mesh.number_of_vertices()), 3);
    py::gil_scoped_release release;
    IM::internal::lift_validated_mesh(mesh, out, np.vertex_normal_map(Vertex_normal_map{normals.data()}));
  };
  if(has_scale)
    with_normals(weights.weight_length_scale(scale));
  else
    with_normals(weights);
}

// The lift of `mesh` for the arguments: compute_lifted_embedding() with the weights as numbers or
// per-vertex maps and the normals and length scale when given.
std::vector<IM::Lifted_point> compute_lift(const Mesh& mesh, const Metric_arguments& a)
{
  const std::size_t n = mesh.number_of_vertices();
  const Weight w(a.euclidean_weight, "euclidean_weight", n), w_prime(a.isophotic_weight, "isophotic_weight", n);
  std::vector<IM::Lifted_point> lifted(n);
  const Lifted_point_writer out{lifted.data()};
  namespace P = IM::parameters;
  if(!w.per_vertex && !w_prime.per_vertex)
    lift_with(mesh, P::euclidean_weight(w.value).isophotic_weight(w_prime.value), a, out);
  else if(!w.per_vertex) // a constant w keeps the lift at the origin, as in C++
    lift_with(mesh, P::euclidean_weight(w.value).isophotic_weight(w_prime.map()), a, out);
  else
    lift_with(mesh, P::euclidean_weight(w.map()).isophotic_weight(w_prime.map()), a, out);
  return lifted;
}

// A number (or None, the default of a weight), not an array.
bool is_number(const py::object& x)
{
  if(x.is_none())
    return true;
  const py::array a = py::array::ensure(x);
  return a && a.ndim() == 0;
}

} // namespace

const Mesh& mesh_of(const py::handle& mesh)
{
  if(py::isinstance<Prepared_mesh>(mesh))
    return py::cast<const Prepared_mesh&>(mesh).mesh();
  return py::cast<const Mesh&>(mesh);
}

// The metric is prepared in one of two ways, so that the prepared mesh is compiled three times, not
// once per combination of weights and normals: from constant weights without normals, as the C++
// functions prepare it themselves (the same edge lengths to the last bit, so the same results), or
// from the lift, computed by compute_lift().
Prepared_mesh prepared_mesh(const py::handle& mesh, const Metric_arguments& a)
{
  if(py::isinstance<Prepared_mesh>(mesh))
  {
    if(a.any_given())
      throw py::value_error("a Metric_mesh has its metric: give euclidean_weight, isophotic_weight, "
                            "weight_length_scale and normals when preparing it, not with it");
    return py::cast<const Prepared_mesh&>(mesh);
  }
  const Mesh& tm = py::cast<const Mesh&>(mesh);
  if(is_number(a.euclidean_weight) && is_number(a.isophotic_weight) && a.normals.is_none())
  {
    const double w_value = a.euclidean_weight.is_none() ? 1. : py::cast<double>(a.euclidean_weight);
    const double w_prime_value = a.isophotic_weight.is_none() ? 1. : py::cast<double>(a.isophotic_weight);
    const auto weights = IM::parameters::euclidean_weight(w_value).isophotic_weight(w_prime_value);
    if(a.weight_length_scale.is_none())
    {
      py::gil_scoped_release release;
      return Prepared_mesh(tm, weights);
    }
    const double L = py::cast<double>(a.weight_length_scale);
    py::gil_scoped_release release;
    return Prepared_mesh(tm, weights.weight_length_scale(L));
  }
  const std::vector<IM::Lifted_point> lifted = compute_lift(tm, a);
  py::gil_scoped_release release;
  return Prepared_mesh(tm, IM::parameters::lifted_embedding_map(Lifted_point_map{lifted.data()}));
}

namespace {

Mesh mesh_from_arrays(const py::handle& V, const py::handle& F)
{
  const Double_array points = as_doubles(V, "V", -1, 3);
  const py::array raw_faces = py::array::ensure(F);
  if(!raw_faces || (raw_faces.dtype().kind() != 'i' && raw_faces.dtype().kind() != 'u'))
    throw py::type_error("F must be an integer array");
  if(raw_faces.ndim() != 2 || raw_faces.shape(1) != 3)
    throw py::value_error("F must have shape (m, 3) (got " + shape_of(raw_faces) + ")");
  const Index_array faces = Index_array::ensure(raw_faces);
  const std::size_t n = std::size_t(points.shape(0)), m = std::size_t(faces.shape(0));

  Mesh mesh;
  mesh.reserve(Mesh::size_type(n), Mesh::size_type(3 * m / 2), Mesh::size_type(m));
  for(std::size_t i = 0; i < n; ++i)
    mesh.add_vertex(Kernel::Point_3(points.at(i, 0), points.at(i, 1), points.at(i, 2)));
  for(std::size_t f = 0; f < m; ++f)
  {
    const std::int64_t a = faces.at(f, 0), b = faces.at(f, 1), c = faces.at(f, 2);
    const std::string what = "face " + std::to_string(f) + " (" + std::to_string(a) + ", " + std::to_string(b) +
                             ", " + std::to_string(c) + ")";
    for(std::int64_t k : {a, b, c})
      if(k < 0 || std::uint64_t(k) >= n)
        throw IM::Invalid_mesh_error(what + " refers to vertex " + std::to_string(k) + "; the mesh has " +
                                     std::to_string(n) + " vertices");
    if(a == b || b == c || c == a)
      throw IM::Invalid_mesh_error(what + " repeats a vertex");
    if(mesh.add_face(Vertex(Mesh::size_type(a)), Vertex(Mesh::size_type(b)), Vertex(Mesh::size_type(c))) ==
       Mesh::null_face())
      throw IM::Invalid_mesh_error(what + " cannot be added: it makes an edge or a vertex non-manifold, or is "
                                   "oriented against a neighbour; repair the mesh or orient its faces consistently");
  }
  IM::validate_triangle_mesh(mesh);
  return mesh;
}

Mesh mesh_from_file(const std::string& path)
{
  if(!std::ifstream(path).good())
    throw py::value_error("cannot open mesh file '" + path + "'");
  Mesh mesh;
  if(!CGAL::IO::read_polygon_mesh(path, mesh) || mesh.has_garbage())
    throw IM::Invalid_mesh_error("cannot read a polygon mesh from '" + path + "' (formats: OFF, OBJ, PLY, STL, ...)");
  IM::validate_triangle_mesh(mesh);
  return mesh;
}

// The vertices of every face from target(halfedge(f)): the rows of F for a mesh built from arrays.
py::array_t<std::int64_t> face_array(const Mesh& mesh)
{
  py::array_t<std::int64_t> F({py::ssize_t(mesh.number_of_faces()), py::ssize_t(3)});
  std::int64_t* out = F.mutable_data();
  for(Face f : mesh.faces())
    for(Vertex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
      *out++ = std::int64_t(std::size_t(v));
  return F;
}

py::array_t<std::int64_t> edge_array(const Mesh& mesh)
{
  py::array_t<std::int64_t> E({py::ssize_t(mesh.number_of_edges()), py::ssize_t(2)});
  std::int64_t* out = E.mutable_data();
  for(Mesh::Edge_index e : mesh.edges())
  {
    *out++ = std::int64_t(std::size_t(mesh.source(mesh.halfedge(e))));
    *out++ = std::int64_t(std::size_t(mesh.target(mesh.halfedge(e))));
  }
  return E;
}

// The vertex positions as a read-only view of the mesh's own storage (kept alive by the array).
py::array vertex_view(py::object self)
{
  const Mesh& mesh = py::cast<const Mesh&>(self);
  static_assert(sizeof(Kernel::Point_3) == 3 * sizeof(double), "points are three packed doubles");
  const double* data = mesh.number_of_vertices() ? &mesh.point(Vertex(0)).x() : nullptr;
  py::array_t<double> V({py::ssize_t(mesh.number_of_vertices()), py::ssize_t(3)}, data, self);
  py::detail::array_proxy(V.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return std::move(V);
}

Metric_arguments metric(py::object w, py::object w_prime, py::object scale, py::object normals)
{
  return Metric_arguments{std::move(w), std::move(w_prime), std::move(scale), std::move(normals)};
}

// The package's exceptions, as Python classes deriving from Error and from the matching built-in.
PyObject* py_error = nullptr;
PyObject* py_invalid_mesh = nullptr;
PyObject* py_invalid_parameter = nullptr;
PyObject* py_invalid_source = nullptr;
PyObject* py_cancelled = nullptr;

PyObject* new_exception(py::module_& m, const char* name, const char* doc, py::tuple bases)
{
  const std::string qualified = std::string("isophotic_metric.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, bases.ptr(), nullptr);
  if(type == nullptr)
    throw py::error_already_set();
  m.add_object(name, py::handle(type));
  return type;
}

void bind_exceptions(py::module_& m)
{
  py_error = new_exception(m, "Error", "Base class of every error raised by the package.",
                           py::make_tuple(py::handle(PyExc_RuntimeError)));
  const py::handle error(py_error), value_error(PyExc_ValueError);
  py_invalid_mesh = new_exception(m, "InvalidMeshError",
                                  "The mesh cannot be processed (non-triangle face, non-manifold, NaN "
                                  "coordinate or normal, zero-length lifted edge, ...).",
                                  py::make_tuple(error, value_error));
  py_invalid_parameter = new_exception(m, "InvalidParameterError",
                                       "A parameter is out of its domain (negative weight or radius, ...).",
                                       py::make_tuple(error, value_error));
  py_invalid_source = new_exception(m, "InvalidSourceError",
                                    "A source, seed or index does not belong to the mesh or is malformed.",
                                    py::make_tuple(error, value_error));
  py_cancelled = new_exception(m, "CancelledError", "A propagation was cancelled by its progress callback.",
                               py::make_tuple(error));
  py::register_exception_translator([](std::exception_ptr p) {
    try
    {
      if(p)
        std::rethrow_exception(p);
    }
    catch(const IM::Invalid_mesh_error& e) { PyErr_SetString(py_invalid_mesh, e.what()); }
    catch(const IM::Invalid_parameter_error& e) { PyErr_SetString(py_invalid_parameter, e.what()); }
    catch(const IM::Invalid_source_error& e) { PyErr_SetString(py_invalid_source, e.what()); }
    catch(const IM::Cancelled_error& e) { PyErr_SetString(py_cancelled, e.what()); }
    catch(const IM::Error& e) { PyErr_SetString(py_error, e.what()); }
  });
}


// ------------------------------------------------------------------ continuous solvers on grids

IM::Fast_sweeping_options sweeping_options(int stencil_radius, bool adaptive_stencil, int source_initialization_radius,
                                           bool second_order, double tolerance, int max_sweeps)
{
  IM::Fast_sweeping_options o;
  o.stencil_radius = stencil_radius;
  o.adaptive_stencil = adaptive_stencil;
  o.source_initialization_radius = source_initialization_radius;
  o.second_order = second_order;
  o.tolerance = tolerance;
  o.max_sweeps = max_sweeps;
  return o;
}

#define ISOPHOTIC_METRIC_PY_SWEEPING_ARGS                                                                \
  py::arg("stencil_radius") = 2, py::arg("adaptive_stencil") = true, py::arg("source_initialization_radius") = 3, \
  py::arg("second_order") = true, py::arg("tolerance") = 1e-12, py::arg("max_sweeps") = 1000

#define ISOPHOTIC_METRIC_PY_SWEEPING_DOC                                                                 \
  "Options (Fast_sweeping_options): stencil_radius (1 or 2), adaptive_stencil, source_initialization_radius,\n" \
  "second_order (3D), tolerance, max_sweeps.\n"

// A grid array (one value per node, the solver's order: first index fastest) as a numpy view of
// shape (nu, nv) or (nx, ny, nz) indexed [i, j(, k)], kept alive by `owner`.
template <class T>
py::array grid_view(const std::vector<T>& values, std::vector<py::ssize_t> shape, py::handle owner)
{
  std::vector<py::ssize_t> strides;
  py::ssize_t stride = sizeof(T);
  for(py::ssize_t n : shape)
  {
    strides.push_back(stride);
    stride *= n;
  }
  py::array_t<T> view(shape, strides, values.data(), owner);
  py::detail::array_proxy(view.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return std::move(view);
}

// Symmetric matrices per node from an array of shape (*grid, d, d), in the solver's node order.
template <int d, class Matrix>
std::vector<Matrix> metric_field(const py::object& metric, const std::vector<py::ssize_t>& grid_shape)
{
  const py::array raw = py::array::ensure(metric);
  std::vector<py::ssize_t> expected = grid_shape;
  expected.push_back(d);
  expected.push_back(d);
  if(!raw || raw.ndim() != py::ssize_t(expected.size()) ||
     !std::equal(expected.begin(), expected.end(), raw.shape()))
    throw py::value_error("metric must have shape (" + std::string(d == 2 ? "nu, nv, 2, 2" : "nx, ny, nz, 3, 3") +
                          "), one symmetric matrix per grid node (got " + shape_of(raw) + ")");
  const Double_array M = Double_array::ensure(raw);
  std::size_t nodes = 1;
  for(py::ssize_t n : grid_shape)
    nodes *= std::size_t(n);
  std::vector<Matrix> field(nodes);
  const double* m = M.data();
  // numpy's C order has the last grid index fastest; the solver's index has the first fastest
  for(std::size_t c = 0; c < nodes; ++c, m += d * d)
  {
    std::size_t rest = c, index = 0, stride = 1;
    std::vector<std::size_t> ijk(grid_shape.size());
    for(std::size_t a = grid_shape.size(); a-- > 0;)
    {
      ijk[a] = rest % std::size_t(grid_shape[a]);
      rest /= std::size_t(grid_shape[a]);
    }
    for(std::size_t a = 0; a < grid_shape.size(); ++a)
    {
      index += ijk[a] * stride;
      stride *= std::size_t(grid_shape[a]);
    }
    field[index] = Eigen::Map<const Eigen::Matrix<double, d, d, Eigen::RowMajor>>(m);
  }
  return field;
}

// A node mask of the grid's shape, in the solver's node order.
std::vector<char> node_mask(const py::object& mask, const std::vector<py::ssize_t>& grid_shape, const char* name)
{
  const py::array raw = py::array::ensure(mask);
  if(!raw || raw.ndim() != py::ssize_t(grid_shape.size()) ||
     !std::equal(grid_shape.begin(), grid_shape.end(), raw.shape()))
    throw py::value_error(std::string(name) + " must be a boolean array of the grid's shape (got " + shape_of(raw) + ")");
  // Fortran order is the solver's order: the first index fastest.
  const auto m = py::array_t<bool, py::array::f_style | py::array::forcecast>::ensure(raw);
  return std::vector<char>(m.data(), m.data() + m.size());
}

// A solver or a field of the continuous side with the shape of its grid, (nu, nv) or (nx, ny, nz):
// the arrays given and returned have that shape (the grid classes are not read for it).
template <class T>
struct With_shape
{
  T value;
  std::vector<py::ssize_t> shape;
};
typedef With_shape<IM::Fast_sweeping_2> Sweeping_2;
typedef With_shape<IM::Fast_sweeping_3> Sweeping_3;
typedef With_shape<IM::Distance_field_2> Field_2;
typedef With_shape<IM::Distance_field_3> Field_3;

template <class Field>
void def_field_properties(py::class_<Field>& c)
{
  c.def_property_readonly("distance", [](py::object self) {
     const Field& f = py::cast<const Field&>(self);
     return grid_view(f.value.distance, f.shape, self);
   }, "Distance per node (read-only view, no copy), +inf where unreached.")
    .def_property_readonly("nearest_source", [](py::object self) {
       const Field& f = py::cast<const Field&>(self);
       return grid_view(f.value.nearest_source, f.shape, self);
     }, "Label of the nearest source per node, -1 if none (read-only view).")
    .def_property_readonly("sweeps", [](const Field& f) { return f.value.sweeps; }, "Number of sweeps done.")
    .def_property_readonly("converged", [](const Field& f) { return f.value.converged; },
                           "False if max_sweeps was reached.");
}

// A pair or array of numbers given as a Python sequence.
template <std::size_t n>
std::array<double, n> numbers(const py::object& sequence, const char* name)
{
  const Double_array a = as_doubles(sequence, name, py::ssize_t(n), 0);
  std::array<double, n> result;
  std::copy(a.data(), a.data() + n, result.begin());
  return result;
}

// The grid shape of a metric array (*grid, d, d).
std::vector<py::ssize_t> grid_shape(const py::object& metric, int d)
{
  const py::array raw = py::array::ensure(metric);
  if(!raw || raw.ndim() != d + 2)
    throw py::value_error(std::string("metric must have shape ") + (d == 2 ? "(nu, nv, 2, 2)" : "(nx, ny, nz, 3, 3)"));
  return std::vector<py::ssize_t>(raw.shape(), raw.shape() + d);
}

void bind_continuous(py::module_& m)
{
  py::class_<Field_2> field_2(m, "Distance_field_2", "Result of Fast_sweeping_2.solve().");
  def_field_properties(field_2);
  field_2.def("interpolate", [](const Field_2& f, double u, double v) { return f.value.interpolate({u, v}); },
              py::arg("u"), py::arg("v"), "Bilinear interpolation of the distance at (u, v).");

  py::class_<Sweeping_2>(m, "Fast_sweeping_2",
                         "Fast-sweeping solver of (grad d)^T M^-1 grad d = 1 on a regular grid of the\n"
                         "parameter rectangle: geodesic distances of a parametric surface in its isophotic\n"
                         "metric M = w I + w' III (first and third fundamental forms sampled at the nodes).")
    .def(py::init([](py::object metric, py::object u_range, py::object v_range, int stencil_radius, bool adaptive,
                     int init_radius, bool second_order, double tolerance, int max_sweeps) {
           const std::vector<py::ssize_t> shape = grid_shape(metric, 2);
           const std::array<double, 2> u = numbers<2>(u_range, "u_range"), v = numbers<2>(v_range, "v_range");
           const IM::Grid_2 grid(u[0], u[1], v[0], v[1], int(shape[0]), int(shape[1]));
           auto field = metric_field<2, Eigen::Matrix2d>(metric, shape);
           return Sweeping_2{IM::Fast_sweeping_2(grid, std::move(field),
                                                 sweeping_options(stencil_radius, adaptive, init_radius, second_order,
                                                                  tolerance, max_sweeps)),
                             shape};
         }),
         py::arg("metric"), py::arg("u_range") = py::make_tuple(0., 1.), py::arg("v_range") = py::make_tuple(0., 1.),
         py::kw_only(), ISOPHOTIC_METRIC_PY_SWEEPING_ARGS,
         "Fast_sweeping_2(metric, u_range=(0, 1), v_range=(0, 1), **options)\n\n"
         "metric: (nu, nv, 2, 2) array, the symmetric positive definite matrix at node (i, j), which\n"
         "sits at (u_min + i hu, v_min + j hv).\n" ISOPHOTIC_METRIC_PY_SWEEPING_DOC)
    .def("add_point_source", [](Sweeping_2& s, double u, double v) { return s.value.add_point_source({u, v}); },
         py::arg("u"), py::arg("v"), "add_point_source(u, v) -> int: a source at a parameter point; its label.")
    .def("add_node_sources",
         [](Sweeping_2& s, py::object mask) { return s.value.add_node_sources(node_mask(mask, s.shape, "mask")); },
         py::arg("mask"), "add_node_sources(mask) -> int: the nodes of a (nu, nv) boolean mask, one label.")
    .def("solve", [](const Sweeping_2& s) {
           py::gil_scoped_release release;
           return Field_2{s.value.solve(), s.shape};
         }, "solve() -> Distance_field_2 (runs without the GIL).")
    .def("trace_back",
         [](const Sweeping_2& s, const Field_2& field, double u, double v) {
           IM::Traced_path_2 path;
           {
             py::gil_scoped_release release;
             path = s.value.trace_back(field.value, {u, v});
           }
           py::array_t<double> uv({py::ssize_t(path.points.size()), py::ssize_t(2)});
           for(std::size_t i = 0; i < path.points.size(); ++i)
             for(int c = 0; c < 2; ++c)
               uv.mutable_at(i, c) = path.points[i][c];
           return py::make_tuple(uv, path.reached_source);
         },
         py::arg("field"), py::arg("u"), py::arg("v"),
         "trace_back(field, u, v) -> ((k, 2) parameter points, reached_source): the curve from (u, v)\n"
         "down the distance field to its source.");

  py::class_<Field_3> field_3(m, "Distance_field_3", "Result of Fast_sweeping_3.solve().");
  def_field_properties(field_3);
  field_3.def("interpolate", [](const Field_3& f, double x, double y, double z) {
    return f.value.interpolate({x, y, z});
  }, py::arg("x"), py::arg("y"), py::arg("z"), "Trilinear interpolation of the distance at a point.");

  py::class_<Sweeping_3>(m, "Fast_sweeping_3",
                         "Solver of (grad d)^T M^-1 grad d = 1 on the active nodes of a 3D grid (a narrow\n"
                         "band around an implicit surface, whose isophotic metric is M = w E + w' J^T J).")
    .def(py::init([](py::object metric, py::object active, py::object origin_xyz, double h, int stencil_radius,
                     bool adaptive, int init_radius, bool second_order, double tolerance, int max_sweeps) {
           const std::vector<py::ssize_t> shape = grid_shape(metric, 3);
           const std::array<double, 3> origin = numbers<3>(origin_xyz, "origin");
           const IM::Grid_3 grid(Eigen::Vector3d(origin[0], origin[1], origin[2]), h, int(shape[0]), int(shape[1]),
                                 int(shape[2]));
           std::vector<char> band = active.is_none() ? std::vector<char>(grid.size(), 1) : node_mask(active, shape, "active");
           auto field = metric_field<3, Eigen::Matrix3d>(metric, shape);
           py::gil_scoped_release release;
           return Sweeping_3{IM::Fast_sweeping_3(grid, std::move(band), std::move(field),
                                                 sweeping_options(stencil_radius, adaptive, init_radius, second_order,
                                                                  tolerance, max_sweeps)),
                             shape};
         }),
         py::arg("metric"), py::arg("active") = py::none(), py::arg("origin") = py::make_tuple(0., 0., 0.),
         py::arg("h") = 1., py::kw_only(), ISOPHOTIC_METRIC_PY_SWEEPING_ARGS,
         "Fast_sweeping_3(metric, active=None, origin=(0, 0, 0), h=1, **options)\n\n"
         "metric: (nx, ny, nz, 3, 3) array, the matrix at node (i, j, k) = origin + h (i, j, k);\n"
         "active: boolean (nx, ny, nz) mask of the band (default: every node).\n" ISOPHOTIC_METRIC_PY_SWEEPING_DOC)
    .def("add_point_source",
         [](Sweeping_3& s, double x, double y, double z) { return s.value.add_point_source({x, y, z}); },
         py::arg("x"), py::arg("y"), py::arg("z"), "add_point_source(x, y, z) -> int: a source at a point; its label.")
    .def("add_node_sources",
         [](Sweeping_3& s, py::object mask) { return s.value.add_node_sources(node_mask(mask, s.shape, "mask")); },
         py::arg("mask"), "add_node_sources(mask) -> int: the nodes of an (nx, ny, nz) boolean mask, one label.")
    .def("solve", [](const Sweeping_3& s) {
           py::gil_scoped_release release;
           return Field_3{s.value.solve(), s.shape};
         }, "solve() -> Distance_field_3 (runs without the GIL).");
}

} // namespace

void bind_mesh_and_metric(py::module_& m)
{
  bind_exceptions(m);
  bind_continuous(m);

  py::class_<Mesh>(m, "Mesh",
                   "A triangle mesh (CGAL::Surface_mesh). Vertex i and face j are row i of V and row j of F;\n"
                   "every index taken or returned by the module refers to these rows.")
    .def(py::init(&mesh_from_arrays), py::arg("V"), py::arg("F"),
         "Mesh(V, F): V an (n, 3) array of vertex positions (float64), F an (m, 3) integer array of\n"
         "vertex indices, consistently oriented. Raises InvalidMeshError for a face that refers to a\n"
         "missing vertex, repeats one, or makes the mesh non-manifold, and for a NaN coordinate.")
    .def(py::init(&mesh_from_file), py::arg("path"),
         "Mesh(path): reads a mesh file (OFF, OBJ, PLY, STL, ...; polygons are oriented and, if\n"
         "needed, made manifold by CGAL's reader). Raises ValueError if the file cannot be opened.")
    .def_property_readonly("vertices", &vertex_view,
                           "(n, 3) float64 read-only view of the vertex positions (no copy).")
    .def_property_readonly("faces", &face_array, "(m, 3) int64 array of the vertex indices of every face.")
    .def_property_readonly("edges", &edge_array,
                           "(e, 2) int64 array of the end vertices of every edge, in the order of\n"
                           "edge_isophotic_lengths().")
    .def_property_readonly("number_of_vertices", [](const Mesh& mesh) { return mesh.number_of_vertices(); },
                           "Number of vertices (rows of V).")
    .def_property_readonly("number_of_faces", [](const Mesh& mesh) { return mesh.number_of_faces(); },
                           "Number of faces (rows of F).")
    .def("__repr__", [](const Mesh& mesh) {
      return "<isophotic_metric.Mesh with " + std::to_string(mesh.number_of_vertices()) + " vertices and " +
             std::to_string(mesh.number_of_faces()) + " faces>";
    });

  py::class_<Prepared_mesh>(m, "Metric_mesh",
                            "A mesh prepared for a metric (C++ Metric_mesh): validated, numbered and its metric edge\n"
                            "lengths computed once. Every function and class that takes a mesh also takes a\n"
                            "Metric_mesh instead (without metric arguments), which saves that set-up when several\n"
                            "calls use the same mesh and metric. It keeps its Mesh alive.")
    .def(py::init([](py::object mesh, py::object w, py::object wp, py::object L, py::object normals) {
           return prepared_mesh(mesh, metric(w, wp, L, normals));
         }),
         py::arg("mesh"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS, py::keep_alive<1, 2>(),
         "Metric_mesh(mesh, *, euclidean_weight=1, isophotic_weight=1, weight_length_scale=None, normals=None)\n\n"
         ISOPHOTIC_METRIC_PY_METRIC_DOC)
    .def_property_readonly("number_of_vertices", &Prepared_mesh::number_of_vertices, "Number of vertices.")
    .def_property_readonly("number_of_faces", &Prepared_mesh::number_of_faces, "Number of faces.");

  m.def("compute_lifted_embedding",
        [](const Mesh& mesh, py::object w, py::object wp, py::object L, py::object normals) {
          std::vector<IM::Lifted_point> lifted = compute_lift(mesh, metric(w, wp, L, normals));
          const py::ssize_t n = py::ssize_t(lifted.size());
          static_assert(sizeof(IM::Lifted_point) == 6 * sizeof(double), "lifted points are six packed doubles");
          auto* owner = new std::vector<IM::Lifted_point>(std::move(lifted));
          py::capsule free_when_done(owner, [](void* p) { delete static_cast<std::vector<IM::Lifted_point>*>(p); });
          return py::array_t<double>({n, py::ssize_t(6)}, owner->data()->data(), free_when_done);
        },
        py::arg("mesh"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS,
        "compute_lifted_embedding(mesh, *, euclidean_weight=1, isophotic_weight=1,\n"
        "                         weight_length_scale=None, normals=None) -> (n, 6) float64 array\n\n"
        "The R^6 lift X(v) = (sqrt(w) p(v), sqrt(w') L n(v)) of every vertex (Pottmann et al. 2004,\n"
        "Remark 1): Euclidean distances on the lifted mesh are isophotic distances on the mesh.\n"
        "With per-vertex euclidean_weight the positions are taken relative to the centroid.\n\n" ISOPHOTIC_METRIC_PY_METRIC_DOC);

  m.def("edge_isophotic_lengths",
        [](const Mesh& mesh, py::object w, py::object wp, py::object L, py::object normals) {
          const std::vector<IM::Lifted_point> lifted = compute_lift(mesh, metric(w, wp, L, normals));
          py::array_t<double> lengths(py::ssize_t(mesh.number_of_edges()));
          double* out = lengths.mutable_data();
          for(Mesh::Edge_index e : mesh.edges())
            *out++ = IM::edge_isophotic_length(e, mesh, Lifted_point_map{lifted.data()});
          return lengths;
        },
        py::arg("mesh"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS,
        "edge_isophotic_lengths(mesh, **metric) -> (e,) float64 array\n\n"
        "The isophotic length of every edge (in the order of mesh.edges):\n"
        "sqrt(w |p_u - p_v|^2 + w' L^2 |n_u - n_v|^2) for constant weights.\n\n" ISOPHOTIC_METRIC_PY_METRIC_DOC);

  m.def("polyline_isophotic_length",
        [](const Mesh& mesh, py::object faces, py::object barycentric, py::object w, py::object wp, py::object L,
           py::object normals) {
          const std::vector<std::uint32_t> f = as_indices(faces, "faces", "face", mesh.number_of_faces());
          const Double_array b = as_doubles(barycentric, "barycentric", py::ssize_t(f.size()), 3);
          std::vector<CGAL::Polygon_mesh_processing::Face_location<Mesh, double>> polyline;
          for(std::size_t i = 0; i < f.size(); ++i)
            polyline.push_back({Face(Mesh::size_type(f[i])), to_cpp_barycentric(b.at(i, 0), b.at(i, 1), b.at(i, 2))});
          const std::vector<IM::Lifted_point> lifted = compute_lift(mesh, metric(w, wp, L, normals));
          return IM::polyline_isophotic_length(polyline, mesh, Lifted_point_map{lifted.data()});
        },
        py::arg("mesh"), py::arg("faces"), py::arg("barycentric"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS,
        "polyline_isophotic_length(mesh, faces, barycentric, **metric) -> float\n\n"
        "The isophotic length of a polyline on the surface given as surface points (faces (k,),\n"
        "barycentric (k, 3) w.r.t. the face's vertices in the order of mesh.faces), for example a\n"
        "path of Geodesic_solver.trace_path(). Consecutive points must lie in a common face.\n\n"
        ISOPHOTIC_METRIC_PY_METRIC_DOC);

  m.def("purely_isophotic_distance",
        [](py::object n1, py::object n2) -> py::object {
          const py::array a = py::array::ensure(n1);
          const bool single = a && a.ndim() == 1;
          auto as_rows = [single](const py::object& n) { return single ? py::array::ensure(n).reshape({1, 3}) : n; };
          const Double_array x = as_doubles(as_rows(n1), "n1", -1, 3);
          const Double_array y = as_doubles(as_rows(n2), "n2", x.shape(0), 3);
          py::array_t<double> d(x.shape(0));
          for(py::ssize_t i = 0; i < x.shape(0); ++i)
            d.mutable_data()[i] = IM::purely_isophotic_distance(Kernel::Vector_3(x.at(i, 0), x.at(i, 1), x.at(i, 2)),
                                                                Kernel::Vector_3(y.at(i, 0), y.at(i, 1), y.at(i, 2)));
          if(single)
            return py::float_(d.at(0));
          return std::move(d);
        },
        py::arg("n1"), py::arg("n2"),
        "purely_isophotic_distance(n1, n2) -> float or (k,) array\n\n"
        "The angle (radians, in [0, pi]) between two normals: the great-circle distance of their\n"
        "Gaussian images. n1, n2: vectors (3,) or arrays (k, 3) of vectors, not necessarily unit.");

  m.def("suggested_weight_length_scale", [](const Mesh& mesh) { return IM::suggested_weight_length_scale(mesh); },
        py::arg("mesh"),
        "suggested_weight_length_scale(mesh) -> float\n\n"
        "A length L that makes the weights dimensionless: the diagonal of the bounding box.");

  // Scans: normals robust to noise, to pass as `normals` to any call or Metric_mesh.
  m.def("estimate_mesh_noise",
        [](const Mesh& mesh) {
          const IM::Mesh_noise_estimate estimate = IM::estimate_mesh_noise(mesh);
          return py::make_tuple(estimate.mean_edge_length, estimate.noise);
        },
        py::arg("mesh"),
        "estimate_mesh_noise(mesh) -> (mean_edge_length, noise)\n\n"
        "The mean edge length and the estimated standard deviation of the noise along the normals\n"
        "(both lengths): the robust (median) spread of each vertex's offset from its neighbours'\n"
        "centroid along its normal.");
  m.def("suggested_normal_smoothing_scale", [](const Mesh& mesh) { return IM::suggested_normal_smoothing_scale(mesh); },
        py::arg("mesh"),
        "suggested_normal_smoothing_scale(mesh) -> float\n\n"
        "A scale for estimate_vertex_normals(): 0 (keep the exact normals) when the estimated noise\n"
        "is below 5 % of the mean edge length, else twice the mean edge length.");
  m.def("estimate_vertex_normals",
        [](const Mesh& mesh, double scale) {
          std::vector<double> normals(3 * mesh.number_of_vertices());
          {
            py::gil_scoped_release release;
            IM::estimate_vertex_normals(mesh, scale, Vertex_normal_writer{normals.data()});
          }
          return to_array(std::move(normals), {py::ssize_t(mesh.number_of_vertices()), 3});
        },
        py::arg("mesh"), py::arg("scale"),
        "estimate_vertex_normals(mesh, scale) -> (n, 3) float64 array\n\n"
        "Unit vertex normals robust to the noise of a scan, at the scale `scale` > 0 (a length: the\n"
        "radius of the features kept), with the package's defaults: a feature-preserving filter of\n"
        "the face normals that keeps sharp edges sharp (manual page Scanned Meshes). Pass them as\n"
        "`normals` to any call or to Metric_mesh:\n"
        "    s = suggested_normal_smoothing_scale(mesh)\n"
        "    normals = estimate_vertex_normals(mesh, s) if s > 0 else None\n"
        "Raises ValueError if scale is not finite and positive.");
}

} // namespace isophotic_metric_python

PYBIND11_MODULE(isophotic_metric, m)
{
  m.doc() = "Geodesics, morphology and segmentation on triangle meshes in the isophotic metric\n"
            "(Pottmann et al., ECCV 2004): the Python side of the CGAL package Isophotic_metric.";
  isophotic_metric_python::bind_mesh_and_metric(m);
  isophotic_metric_python::bind_geodesics(m);
  isophotic_metric_python::bind_morphology(m);
  isophotic_metric_python::bind_segmentation(m);
}
