// Copyright (c) 2026 The Isophotic_metric developers.
// This file is part of the Isophotic_metric package (package_info/Isophotic_metric/license.txt).
// SPDX-License-Identifier: GPL-3.0-or-later
//
// A camera that looks at a result on a mesh (a selection, a source, a path), for pictures rendered
// with f3d; shared by the command-line tool and the demo.
#ifndef ISOPHOTIC_TOOLS_VIEW_CAMERA_H
#define ISOPHOTIC_TOOLS_VIEW_CAMERA_H

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/bbox.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

namespace view_camera {

template <class Mesh>
struct View
{
  typedef typename CGAL::Kernel_traits<typename Mesh::Point>::Kernel K;
  typename K::Point_3 eye, focal;
  typename K::Vector_3 up;
  double angle = 30; // vertical view angle, degrees

  // The picture's horizontal direction (unit).
  typename K::Vector_3 right() const
  {
    typename K::Vector_3 r = CGAL::cross_product(focal - eye, up);
    return r / std::sqrt(r.squared_length());
  }

  // The camera as f3d's command-line options.
  std::vector<std::string> f3d_arguments() const
  {
    auto triple = [](double x, double y, double z) {
      std::ostringstream s;
      s << std::setprecision(9) << x << "," << y << "," << z;
      return s.str();
    };
    return {"--camera-position=" + triple(eye.x(), eye.y(), eye.z()),
            "--camera-focal-point=" + triple(focal.x(), focal.y(), focal.z()),
            "--camera-view-up=" + triple(up.x(), up.y(), up.z()), "--camera-view-angle=" + std::to_string(angle)};
  }
};

// Looks at the area-weighted centre of the faces `focus` (at the centre of the model when
// `whole_model`) from the side of their mean normal, slightly from above, far enough to frame them
// (or the whole model). When the normals cancel (a selection all around a part, the whole surface),
// the view is oblique, from (1, -1.2, 0.8). The camera never goes behind another part of the mesh:
// it stays in front of the first surface hit along the viewing ray and widens its view angle
// instead (a seed inside a ring is seen from inside the ring).
template <class Mesh>
View<Mesh> view_of(const Mesh& m, const std::vector<typename Mesh::Face_index>& focus, bool whole_model)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  typedef View<Mesh> Result;
  typedef typename Result::K K;
  typedef typename K::Vector_3 Vector;
  const double pi = 3.14159265358979323846;
  const CGAL::Bbox_3 box = PMP::bbox(m);
  const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                    CGAL::square(box.zmax() - box.zmin()));
  Vector centre(0, 0, 0), normal(0, 0, 0);
  double area = 0;
  for(auto f : focus)
  {
    const double a = PMP::face_area(f, m);
    for(auto v : CGAL::vertices_around_face(halfedge(f, m), m))
      centre = centre + (a / 3) * (m.point(v) - CGAL::ORIGIN);
    normal = normal + a * PMP::compute_face_normal(f, m);
    area += a;
  }
  Result view;
  view.focal = CGAL::ORIGIN + (area > 0 ? centre / area : centre);
  double extent = 0.1 * diagonal;
  for(auto f : focus)
    for(auto v : CGAL::vertices_around_face(halfedge(f, m), m))
      extent = std::max(extent, std::sqrt(CGAL::squared_distance(m.point(v), view.focal)));
  if(whole_model)
  {
    view.focal = CGAL::ORIGIN + 0.5 * Vector(box.xmin() + box.xmax(), box.ymin() + box.ymax(), box.zmin() + box.zmax());
    extent = 0.5 * diagonal;
  }
  if(!(normal.squared_length() > 1e-4 * area * area))
    normal = Vector(1, -1.2, 0.8);
  normal = normal / std::sqrt(normal.squared_length());

  view.up = std::abs(normal.z()) < 0.9 ? Vector(0, 0, 1) : Vector(0, 1, 0);
  Vector direction = normal + 0.35 * (view.up - (view.up * normal) * normal);
  direction = direction / std::sqrt(direction.squared_length());
  const double tan_half = std::tan(view.angle / 2 * pi / 180);
  double distance = 1.2 * extent / tan_half;
  if(!whole_model) // from the centre of the model, every ray meets the model
  {
    typedef CGAL::AABB_face_graph_triangle_primitive<Mesh> Primitive;
    CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>> tree(faces(m).first, faces(m).second, m);
    const typename K::Ray_3 ray(view.focal + 1e-3 * diagonal * direction, direction);
    if(const auto hit = tree.first_intersection(ray))
      if(const auto* p = boost::get<typename K::Point_3>(&hit->first))
        distance = std::min(distance, 0.9 * std::sqrt(CGAL::squared_distance(*p, view.focal)));
  }
  view.angle = std::clamp(2 * std::atan(1.2 * extent / distance) * 180 / pi, view.angle, 110.);
  view.eye = view.focal + distance * direction;
  return view;
}

} // namespace view_camera

#endif // ISOPHOTIC_TOOLS_VIEW_CAMERA_H
