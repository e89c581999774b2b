// Umbrella header of the Isophotic_metric package: includes every public header.
#ifndef CGAL_ISOPHOTIC_METRIC_H
#define CGAL_ISOPHOTIC_METRIC_H

#include <CGAL/Isophotic_metric/exceptions.h>
#include <CGAL/Isophotic_metric/Named_function_parameters.h>

#endif // CGAL_ISOPHOTIC_METRIC_H
