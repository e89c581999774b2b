// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// Python bindings of the morphology and segmentation side: binary, label and grey-level morphology,
// geodesic neighbourhoods, region growing and segmentation. Every call hands the C++ function the
// prepared mesh (named parameter metric_mesh), so each function is compiled once, whatever the
// metric arguments.
#include "module.h"

#include <CGAL/Isophotic_metric/Morphology/Face_band_solver.h>
#include <CGAL/Isophotic_metric/Morphology/face_selection_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/geodesic_neighborhoods.h>
#include <CGAL/Isophotic_metric/Morphology/grey_level_morphology.h>
#include <CGAL/Isophotic_metric/Morphology/label_morphology.h>
#include <CGAL/Isophotic_metric/Segmentation/region_growing.h>

#include <CGAL/iterator.h>

#include <functional>
#include <tuple>
#include <memory>

namespace isophotic_metric_python {

namespace {

// The named parameters of a call: the prepared mesh and the area settings.
auto band_parameters(const Prepared_mesh& prepared, double fraction, int resolution)
{
  return IM::parameters::metric_mesh(prepared).area_fraction(fraction).area_resolution(resolution);
}

// Per-element values held by an array (face or vertex keys), as a read-write property map.
template <class T, class Key = Face>
struct Array_map
{
  typedef Key key_type;
  typedef T value_type;
  typedef T& reference;
  typedef boost::read_write_property_map_tag category;
  T* values;
  friend T get(const Array_map& m, Key k) { return m.values[std::size_t(k)]; }
  friend void put(const Array_map& m, Key k, const T& v) { m.values[std::size_t(k)] = v; }
};

template <class T>
using Vertex_array_map = Array_map<T, Vertex>;

std::vector<Face> faces_of(const std::vector<std::uint32_t>& ids)
{
  std::vector<Face> faces;
  faces.reserve(ids.size());
  for(std::uint32_t i : ids)
    faces.push_back(Face(Mesh::size_type(i)));
  return faces;
}

py::array_t<bool> mask_of(const Mesh& mesh, const std::vector<std::uint32_t>& ids)
{
  py::array_t<bool> mask(py::ssize_t(mesh.number_of_faces()));
  std::fill(mask.mutable_data(), mask.mutable_data() + mask.size(), false);
  for(std::uint32_t i : ids)
    mask.mutable_data()[i] = true;
  return mask;
}

// A copy of the labels (m,) as int64, the array the label operations update and return.
py::array_t<std::int64_t> label_copy(const Mesh& mesh, const py::object& labels)
{
  const py::array raw = py::array::ensure(labels);
  if(!raw || (raw.dtype().kind() != 'i' && raw.dtype().kind() != 'u'))
    throw py::type_error("labels must be an integer array with one label per face");
  if(raw.ndim() != 1 || std::size_t(raw.shape(0)) != mesh.number_of_faces())
    throw py::value_error("labels must have shape (" + std::to_string(mesh.number_of_faces()) + ",), one label per face");
  py::array_t<std::int64_t> copy(raw.shape(0));
  const Index_array given = Index_array::ensure(raw);
  std::copy(given.data(), given.data() + given.size(), copy.mutable_data());
  return copy;
}

#define ISOPHOTIC_METRIC_PY_MORPHOLOGY_ARGS \
  py::arg("area_fraction") = 0., py::arg("area_resolution") = 4, ISOPHOTIC_METRIC_PY_METRIC_ARGS, ISOPHOTIC_METRIC_PY_PROGRESS_ARG

#define ISOPHOTIC_METRIC_PY_PROGRESS_ARG py::arg("progress") = py::none()

#define ISOPHOTIC_METRIC_PY_PROGRESS_DOC                                                                       \
  "progress: None, or a callable progress(advancement) -> bool told now and then of the advancement\n"      \
  "    in [0, 1] of the current propagation or loop; returning False cancels (CancelledError).\n"          \
  "    Ctrl-C interrupts the call (KeyboardInterrupt).\n"

#define ISOPHOTIC_METRIC_PY_MORPHOLOGY_DOC                                                                       \
  "area_fraction: with a > 0 a face counts as reached when at least the fraction a of its area lies\n"         \
  "    within the radius (default 0: when it meets the disc).\n"                                                \
  "area_resolution: n, faces are subdivided into n^2 sub-triangles for the area fraction (default 4).\n"       \
  ISOPHOTIC_METRIC_PY_METRIC_DOC ISOPHOTIC_METRIC_PY_PROGRESS_DOC

// Binds one binary operation: `operation(band, selection_faces, radius, is_selected, np)`.
template <class Operation>
void def_selection_operation(py::module_& m, const char* name, const char* doc, Operation operation)
{
  m.def(name,
        [operation](py::object mesh_or_prepared, py::object selection, double radius, double fraction, int resolution,
                    py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const std::vector<std::uint32_t> ids = as_indices(selection, "selection", "face", mesh.number_of_faces(), true);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          py::array_t<bool> selected = mask_of(mesh, ids);
          const Array_map<bool> is_selected{selected.mutable_data()};
          run_interruptible([&](const Callback& callback) {
            operation(mesh, faces_of(ids), radius, is_selected, band_parameters(prepared, fraction, resolution).callback(callback));
          }, progress);
          return selected;
        },
        py::arg("mesh"), py::arg("selection"), py::arg("radius"), py::kw_only(), ISOPHOTIC_METRIC_PY_MORPHOLOGY_ARGS,
        doc);
}

// Binds one label operation: `operation(mesh, radius, labels_map, unlabelled, np)`.
template <class Operation>
void def_label_operation(py::module_& m, const char* name, const char* doc, Operation operation)
{
  m.def(name,
        [operation](py::object mesh_or_prepared, py::object labels, double radius, std::int64_t unlabelled,
                    double fraction, int resolution, py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          py::array_t<std::int64_t> result = label_copy(mesh, labels);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          const Array_map<std::int64_t> map{result.mutable_data()};
          run_interruptible([&](const Callback& callback) {
            operation(mesh, radius, map, unlabelled, band_parameters(prepared, fraction, resolution).callback(callback));
          }, progress);
          return result;
        },
        py::arg("mesh"), py::arg("labels"), py::arg("radius"), py::kw_only(), py::arg("unlabelled") = -1,
        ISOPHOTIC_METRIC_PY_MORPHOLOGY_ARGS, doc);
}

IM::Field_location field_location(const std::string& where)
{
  if(where == "vertices")
    return IM::Field_location::VERTICES;
  if(where == "faces")
    return IM::Field_location::FACES;
  throw py::value_error("location must be 'vertices' or 'faces' (got '" + where + "')");
}

// Grey-level morphology with the neighbourhoods computed once; a Python structuring function is
// called with the GIL held (fields are processed in the calling thread).
struct Grey_level
{
  py::object structuring_function;
  std::unique_ptr<IM::Grey_level_morphology<Mesh>> morphology;

  py::array_t<double> apply(const py::object& values,
                            std::vector<double> (IM::Grey_level_morphology<Mesh>::*operation)(const std::vector<double>&) const)
  {
    const Double_array u = as_doubles(values, "values", py::ssize_t(morphology->size()), 0);
    std::vector<double> field(u.data(), u.data() + u.size());
    std::vector<double> result;
    if(structuring_function.is_none())
    {
      py::gil_scoped_release release;
      result = ((*morphology).*operation)(field);
    }
    else
      result = ((*morphology).*operation)(field);
    const py::ssize_t n = py::ssize_t(result.size());
    return to_array(std::move(result), {n});
  }
};

std::unique_ptr<Grey_level> make_grey_level(py::object mesh, double radius, const std::string& where,
                                            py::object structuring_function, const Metric_arguments& metric,
                                            const py::object& progress)
{
  auto grey = std::make_unique<Grey_level>();
  grey->structuring_function = std::move(structuring_function);
  const Grey_level* self = grey.get(); // the function reads the callable through this stable pointer
  std::function<double(double)> b = [](double) { return 0.; };
  if(!grey->structuring_function.is_none())
    b = [self](double d) { return py::cast<double>(self->structuring_function(d)); };
  const IM::Field_location location = field_location(where);
  const Prepared_mesh prepared = prepared_mesh(mesh, metric);
  run_interruptible([&](const Callback& callback) {
    grey->morphology = std::make_unique<IM::Grey_level_morphology<Mesh>>(
      prepared.mesh(), radius, location, IM::parameters::metric_mesh(prepared).structuring_function(b).callback(callback));
  }, progress);
  return grey;
}

// Neighbourhood lists as compressed rows: offsets (k+1,), indices and distances; `entry` gives the
// (index, distance) of an element of a list.
template <class List, class Entry>
py::tuple compressed_rows(const std::vector<List>& lists, Entry entry)
{
  std::size_t total = 0;
  for(const List& l : lists)
    total += l.size();
  py::array_t<std::int64_t> offsets(py::ssize_t(lists.size() + 1));
  py::array_t<std::int64_t> indices{py::ssize_t(total)};
  py::array_t<double> distances{py::ssize_t(total)};
  std::int64_t* o = offsets.mutable_data();
  std::int64_t* i = indices.mutable_data();
  double* d = distances.mutable_data();
  *o++ = 0;
  std::int64_t k = 0;
  for(const List& l : lists)
  {
    for(const auto& e : l)
      std::tie(*i++, *d++) = entry(e);
    k += std::int64_t(l.size());
    *o++ = k;
  }
  return py::make_tuple(offsets, indices, distances);
}

} // namespace

void bind_morphology(py::module_& m)
{
  namespace P = IM::parameters;

  def_selection_operation(
    m, "dilate_face_selection",
    "dilate_face_selection(mesh, selection, radius, *, area_fraction=0, area_resolution=4, **metric)\n"
    "    -> (m,) bool mask\n\n"
    "Dilates a face selection (indices or a boolean mask) by a metric radius: a face joins when it\n"
    "comes within radius of the selection in the isophotic metric (exact distance to the union of\n"
    "the selected closed faces, one bounded propagation).\n" ISOPHOTIC_METRIC_PY_MORPHOLOGY_DOC,
    [](const Mesh& mesh, const std::vector<Face>& selection, double radius, auto is_selected, const auto& np) {
      IM::dilate_face_selection(selection, mesh, radius, is_selected, CGAL::Emptyset_iterator(), np);
    });
  def_selection_operation(
    m, "erode_face_selection",
    "erode_face_selection(mesh, selection, radius, **options) -> (m,) bool mask\n\n"
    "Erodes a face selection: a selected face leaves when it comes within radius of the\n"
    "unselected faces (the dual of dilate_face_selection; options as there).",
    [](const Mesh& mesh, const std::vector<Face>& selection, double radius, auto is_selected, const auto& np) {
      IM::erode_face_selection(selection, mesh, radius, is_selected, CGAL::Emptyset_iterator(), np);
    });
  def_selection_operation(
    m, "open_face_selection",
    "open_face_selection(mesh, selection, radius, **options) -> (m,) bool mask\n\n"
    "Opening (erosion, then dilation): removes the parts of the selection narrower than the disc.",
    [](const Mesh& mesh, const std::vector<Face>&, double radius, auto is_selected, const auto& np) {
      IM::open_face_selection(mesh, radius, is_selected, np);
    });
  def_selection_operation(
    m, "close_face_selection",
    "close_face_selection(mesh, selection, radius, **options) -> (m,) bool mask\n\n"
    "Closing (dilation, then erosion): fills the gaps of the selection narrower than the disc.",
    [](const Mesh& mesh, const std::vector<Face>&, double radius, auto is_selected, const auto& np) {
      IM::close_face_selection(mesh, radius, is_selected, np);
    });

  def_label_operation(
    m, "dilate_face_labels",
    "dilate_face_labels(mesh, labels, radius, *, unlabelled=-1, area_fraction=0, area_resolution=4,\n"
    "                   **metric) -> (m,) int64 labels\n\n"
    "Grows every label into the unlabelled faces within radius (a geodesic Voronoi partition of\n"
    "the band around the labelled faces). The input array is not modified.\n" ISOPHOTIC_METRIC_PY_MORPHOLOGY_DOC,
    [](const Mesh& mesh, double radius, auto labels, std::int64_t unlabelled, const auto& np) {
      IM::dilate_face_labels(mesh, radius, labels, unlabelled, np);
    });
  def_label_operation(
    m, "erode_face_labels",
    "erode_face_labels(mesh, labels, radius, **options) -> (m,) int64 labels\n\n"
    "A labelled face becomes unlabelled when it comes within radius of a face without its label.",
    [](const Mesh& mesh, double radius, auto labels, std::int64_t unlabelled, const auto& np) {
      IM::erode_face_labels(mesh, radius, labels, unlabelled, np);
    });
  def_label_operation(
    m, "open_face_labels",
    "open_face_labels(mesh, labels, radius, **options) -> (m,) int64 labels\n\n"
    "Opening of every class (erosion, then dilation within the class's own erosion).",
    [](const Mesh& mesh, double radius, auto labels, std::int64_t unlabelled, const auto& np) {
      IM::open_face_labels(mesh, radius, labels, unlabelled, np);
    });
  def_label_operation(
    m, "close_face_labels",
    "close_face_labels(mesh, labels, radius, **options) -> (m,) int64 labels\n\n"
    "Closing of every class; an unlabelled face claimed by exactly one class takes its label.",
    [](const Mesh& mesh, double radius, auto labels, std::int64_t unlabelled, const auto& np) {
      IM::close_face_labels(mesh, radius, labels, unlabelled, np);
    });

  m.def("series_close_face_labels",
        [](py::object mesh_or_prepared, py::object labels, py::object radii, std::int64_t unlabelled, double fraction,
           int resolution, py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const Double_array r = as_doubles(radii, "radii", -1, 0);
          const std::vector<double> radius_list(r.data(), r.data() + r.size());
          py::array_t<std::int64_t> result = label_copy(mesh, labels);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          run_interruptible([&](const Callback& callback) {
            IM::series_close_face_labels(mesh, radius_list, Array_map<std::int64_t>{result.mutable_data()},
                                         unlabelled, band_parameters(prepared, fraction, resolution).callback(callback));
          }, progress);
          return result;
        },
        py::arg("mesh"), py::arg("labels"), py::arg("radii"), py::kw_only(), py::arg("unlabelled") = -1,
        ISOPHOTIC_METRIC_PY_MORPHOLOGY_ARGS,
        "series_close_face_labels(mesh, labels, radii, **options) -> (m,) int64 labels\n\n"
        "Closings of increasing radius (Hanbury's series closing of a partition), each applied to the\n"
        "result of the previous one.");

  py::class_<Grey_level>(m, "Grey_level_morphology",
                         "Grey-level morphology of scalar fields on the mesh ('images on surfaces'): the\n"
                         "geodesic neighbourhoods of every vertex (or face centroid) are computed once, then\n"
                         "fields are dilated, eroded, opened and closed. With a structuring function b of\n"
                         "the distance: (dilate u)(x) = max over d(x,y) <= r of u(y) + b(d(x,y)).")
    .def(py::init([](py::object mesh, double radius, const std::string& location, py::object structuring_function,
                     py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
           return make_grey_level(mesh, radius, location, structuring_function, Metric_arguments{w, wp, L, normals}, progress);
         }),
         py::arg("mesh"), py::arg("radius"), py::kw_only(), py::arg("location") = "vertices",
         py::arg("structuring_function") = py::none(), ISOPHOTIC_METRIC_PY_METRIC_ARGS, ISOPHOTIC_METRIC_PY_PROGRESS_ARG, py::keep_alive<1, 2>(),
         "Grey_level_morphology(mesh, radius, *, location='vertices', structuring_function=None, **metric)\n\n"
         "location: 'vertices' (one value per vertex) or 'faces' (per face, neighbourhoods between\n"
         "    face centroids).\n"
         "structuring_function: None (flat) or a callable b(distance) -> float, e.g. lambda d: -k*d*d.\n"
         ISOPHOTIC_METRIC_PY_METRIC_DOC ISOPHOTIC_METRIC_PY_PROGRESS_DOC)
    .def("dilate", [](Grey_level& g, py::object u) { return g.apply(u, &IM::Grey_level_morphology<Mesh>::dilate); },
         py::arg("values"), "dilate(values) -> array: grey-level dilation (max over the neighbourhood).")
    .def("erode", [](Grey_level& g, py::object u) { return g.apply(u, &IM::Grey_level_morphology<Mesh>::erode); },
         py::arg("values"), "erode(values) -> array: grey-level erosion (min over the transposed neighbourhood).")
    .def("open", [](Grey_level& g, py::object u) { return g.apply(u, &IM::Grey_level_morphology<Mesh>::open); },
         py::arg("values"), "open(values) -> array: erosion then dilation (removes narrow peaks).")
    .def("close", [](Grey_level& g, py::object u) { return g.apply(u, &IM::Grey_level_morphology<Mesh>::close); },
         py::arg("values"), "close(values) -> array: dilation then erosion (fills narrow valleys).");

  m.def("geodesic_neighborhood",
        [](py::object mesh_or_prepared, py::object center, double radius, const std::string& kind,
           py::object barycentric, double fraction, int resolution, py::object w, py::object wp, py::object L,
           py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          const auto np = band_parameters(prepared, fraction, resolution);
          std::vector<IM::Neighborhood_face<Face>> result;
          if(kind == "face" || kind == "point")
          {
            const auto f = as_indices(center, "center", "face", mesh.number_of_faces());
            if(kind == "face")
              run_interruptible([&](const Callback& callback) {
                IM::geodesic_neighborhood(Face(Mesh::size_type(f.at(0))), mesh, radius, std::back_inserter(result),
                                          np.callback(callback));
              }, progress);
            else
            {
              const Double_array b = as_doubles(barycentric, "barycentric", -1, 0);
              if(b.size() != 3)
                throw py::value_error("barycentric must have shape (3,)");
              const IM::Geodesic_solver<Mesh>::Face_location p(Face(Mesh::size_type(f.at(0))),
                                                               to_cpp_barycentric(b.at(0), b.at(1), b.at(2)));
              run_interruptible([&](const Callback& callback) {
                IM::geodesic_neighborhood(p, mesh, radius, std::back_inserter(result), np.callback(callback));
              }, progress);
            }
          }
          else if(kind == "vertex")
          {
            const auto v = as_indices(center, "center", "vertex", mesh.number_of_vertices());
            run_interruptible([&](const Callback& callback) {
              IM::geodesic_neighborhood(Vertex(Mesh::size_type(v.at(0))), mesh, radius, std::back_inserter(result),
                                        np.callback(callback));
            }, progress);
          }
          else
            throw py::value_error("kind must be 'face', 'vertex' or 'point' (got '" + kind + "')");
          py::array_t<std::int64_t> faces(py::ssize_t(result.size()));
          py::array_t<double> distance(py::ssize_t(result.size())), fraction_covered(py::ssize_t(result.size()));
          for(std::size_t i = 0; i < result.size(); ++i)
          {
            faces.mutable_at(i) = std::int64_t(std::size_t(result[i].face));
            distance.mutable_at(i) = result[i].min_distance;
            fraction_covered.mutable_at(i) = result[i].covered_fraction;
          }
          return py::make_tuple(faces, distance, fraction_covered);
        },
        py::arg("mesh"), py::arg("center"), py::arg("radius"), py::kw_only(), py::arg("kind") = "face",
        py::arg("barycentric") = py::none(), ISOPHOTIC_METRIC_PY_MORPHOLOGY_ARGS,
        "geodesic_neighborhood(mesh, center, radius, *, kind='face', barycentric=None, **options)\n"
        "    -> (faces, min_distance, covered_fraction)\n\n"
        "The faces within radius of a closed face (kind='face'), a vertex ('vertex') or a surface point\n"
        "('point': center is the face, barycentric its coordinates): the geodesic disc used as\n"
        "structuring element. covered_fraction is -1 unless area_fraction > 0.\n" ISOPHOTIC_METRIC_PY_MORPHOLOGY_DOC);

  m.def("all_face_neighborhoods",
        [](py::object mesh_or_prepared, double radius, const std::string& center, double fraction, int resolution,
           py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          if(center != "face" && center != "centroid")
            throw py::value_error("center must be 'face' or 'centroid' (got '" + center + "')");
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          std::vector<std::vector<IM::Neighborhood_face<Face>>> lists(mesh.number_of_faces());
          run_interruptible([&](const Callback& callback) {
            IM::all_face_neighborhoods(
              mesh, radius, Array_map<std::vector<IM::Neighborhood_face<Face>>>{lists.data()},
              band_parameters(prepared, fraction, resolution)
                .neighborhood_center(center == "face" ? IM::Neighborhood_center::FACE : IM::Neighborhood_center::FACE_CENTROID)
                .callback(callback));
          }, progress);
          return compressed_rows(lists, [](const IM::Neighborhood_face<Face>& e) {
            return std::make_pair(std::int64_t(std::size_t(e.face)), e.min_distance);
          });
        },
        py::arg("mesh"), py::arg("radius"), py::kw_only(), py::arg("center") = "face",
        ISOPHOTIC_METRIC_PY_MORPHOLOGY_ARGS,
        "all_face_neighborhoods(mesh, radius, *, center='face', **options) -> (offsets, faces, distances)\n\n"
        "The neighbourhood of every face (center 'face': the closed face, 'centroid': its centroid), as\n"
        "compressed rows: face i sees faces[offsets[i]:offsets[i+1]] with the smallest distance found\n"
        "on each. Parallel with TBB when available.");

  m.def("all_vertex_neighborhoods",
        [](py::object mesh_or_prepared, double radius, py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          std::vector<std::vector<IM::Neighborhood_vertex<Vertex>>> lists(mesh.number_of_vertices());
          run_interruptible([&](const Callback& callback) {
            IM::all_vertex_neighborhoods(mesh, radius, Vertex_array_map<std::vector<IM::Neighborhood_vertex<Vertex>>>{lists.data()},
                                         P::metric_mesh(prepared).callback(callback));
          }, progress);
          return compressed_rows(lists, [](const IM::Neighborhood_vertex<Vertex>& e) {
            return std::make_pair(std::int64_t(std::size_t(e.vertex)), e.distance);
          });
        },
        py::arg("mesh"), py::arg("radius"), py::kw_only(), ISOPHOTIC_METRIC_PY_METRIC_ARGS, ISOPHOTIC_METRIC_PY_PROGRESS_ARG,
        "all_vertex_neighborhoods(mesh, radius, **metric) -> (offsets, vertices, distances)\n\n"
        "The vertices within radius of every vertex with their exact distances, as compressed rows.\n"
        ISOPHOTIC_METRIC_PY_PROGRESS_DOC);

  m.def("grow_region",
        [](py::object mesh_or_prepared, py::object seeds, double radius, double fraction, py::object predicate,
           int resolution, py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const auto ids = as_indices(seeds, "seeds", "face", mesh.number_of_faces(), true);
          std::function<bool(Face)> accept = [](Face) { return true; };
          py::array_t<bool> allowed;
          if(!predicate.is_none())
          {
            allowed = py::array_t<bool>::ensure(predicate);
            if(!allowed || allowed.ndim() != 1 || std::size_t(allowed.shape(0)) != mesh.number_of_faces())
              throw py::value_error("face_predicate must be a boolean mask with one entry per face");
            const bool* mask = allowed.data();
            accept = [mask](Face f) { return mask[std::size_t(f)]; };
          }
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          std::vector<Face> region;
          run_interruptible([&](const Callback& callback) {
            IM::grow_region(faces_of(ids), mesh, radius, std::back_inserter(region),
                            band_parameters(prepared, fraction, resolution).face_predicate(accept).callback(callback));
          }, progress);
          std::vector<std::uint32_t> region_ids;
          for(Face f : region)
            region_ids.push_back(std::uint32_t(std::size_t(f)));
          return mask_of(mesh, region_ids);
        },
        py::arg("mesh"), py::arg("seeds"), py::arg("radius"), py::kw_only(), py::arg("area_fraction") = 0.,
        py::arg("face_predicate") = py::none(), py::arg("area_resolution") = 4, ISOPHOTIC_METRIC_PY_METRIC_ARGS, ISOPHOTIC_METRIC_PY_PROGRESS_ARG,
        "grow_region(mesh, seeds, radius, *, area_fraction=0, face_predicate=None, **options)\n"
        "    -> (m,) bool mask\n\n"
        "Grows a region from seed faces: the faces within radius of the seeds (at least area_fraction\n"
        "of their area), allowed by face_predicate (a boolean mask over the faces) and edge-connected\n"
        "to the seeds through such faces. It spreads along features and stops at them.\n"
        ISOPHOTIC_METRIC_PY_PROGRESS_DOC);

  m.def("partition_by_nearest_seed",
        [](py::object mesh_or_prepared, py::list seeds, double max_distance, py::object w, py::object wp,
           py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          std::vector<std::vector<Face>> seed_faces;
          std::size_t i = 0;
          for(py::handle seed : seeds)
          {
            const std::string name = "seeds[" + std::to_string(i++) + "]";
            seed_faces.push_back(faces_of(as_indices(seed, name.c_str(), "face", mesh.number_of_faces(), true)));
          }
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          py::array_t<std::int64_t> patch(py::ssize_t(mesh.number_of_faces()));
          run_interruptible([&](const Callback& callback) {
            IM::partition_by_nearest_seed(seed_faces, mesh, Array_map<std::int64_t>{patch.mutable_data()},
                                          P::metric_mesh(prepared).max_distance(max_distance).callback(callback));
          }, progress);
          return patch;
        },
        py::arg("mesh"), py::arg("seeds"), py::kw_only(), py::arg("max_distance") = std::numeric_limits<double>::infinity(),
        ISOPHOTIC_METRIC_PY_METRIC_ARGS, ISOPHOTIC_METRIC_PY_PROGRESS_ARG,
        "partition_by_nearest_seed(mesh, seeds, *, max_distance=inf, **metric) -> (m,) int64\n\n"
        "Geodesic Voronoi partition: seeds is a list of face sets (indices or masks); every face whose\n"
        "centroid is within max_distance gets the index of the nearest seed, the others len(seeds).\n"
        ISOPHOTIC_METRIC_PY_PROGRESS_DOC);

  m.def("segment_by_region_growing",
        [](py::object mesh_or_prepared, double radius, double fraction, double merge_tolerance, int resolution,
           py::object w, py::object wp, py::object L, py::object normals, py::object progress) {
          const Mesh& mesh = mesh_of(mesh_or_prepared);
          const Prepared_mesh prepared = prepared_mesh(mesh_or_prepared, Metric_arguments{w, wp, L, normals});
          py::array_t<std::int64_t> patch(py::ssize_t(mesh.number_of_faces()));
          run_interruptible([&](const Callback& callback) {
            IM::segment_by_region_growing(
              mesh, radius, Array_map<std::int64_t>{patch.mutable_data()},
              band_parameters(prepared, fraction, resolution).merge_tolerance(merge_tolerance).callback(callback));
          }, progress);
          return patch;
        },
        py::arg("mesh"), py::arg("radius"), py::kw_only(), py::arg("area_fraction") = 0.,
        py::arg("merge_tolerance") = 0.5, py::arg("area_resolution") = 4, ISOPHOTIC_METRIC_PY_METRIC_ARGS, ISOPHOTIC_METRIC_PY_PROGRESS_ARG,
        "segment_by_region_growing(mesh, radius, *, area_fraction=0, merge_tolerance=0.5, **metric)\n"
        "    -> (m,) int64 patch index of every face\n\n"
        "Segmentation by region growing in the isophotic metric (greedy cover by regions of the given\n"
        "radius), then merging of the patches whose common boundary is not a feature (stretch of the\n"
        "metric within the factor 1 + merge_tolerance; negative: no merge). Patches numbered from 0.\n"
        ISOPHOTIC_METRIC_PY_PROGRESS_DOC);
}

} // namespace isophotic_metric_python
