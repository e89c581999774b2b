// Umbrella header of the Isophotic_metric package: includes every public header.
#ifndef CGAL_ISOPHOTIC_METRIC_H
#define CGAL_ISOPHOTIC_METRIC_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>
#include <CGAL/Isophotic_metric/validate_triangle_mesh.h>
#include <CGAL/Isophotic_metric/compute_lifted_embedding.h>
#include <CGAL/Isophotic_metric/suggested_weight_length_scale.h>
#include <CGAL/Isophotic_metric/isophotic_length.h>

#endif // CGAL_ISOPHOTIC_METRIC_H
