// Spheres and disks as Embree user geometry, intersected analytically (double precision).
#pragma once

#include <embree3/rtcore.h>

#include "geometry/geometry_scene.hpp"

namespace nimbus {

// Creates the user geometry for a sphere or disk record (its address is the user pointer, so the record
// must not move while the scene lives).
RTCGeometry make_analytic_geometry(RTCDevice device, const ShapeRecord &shape);

}  // namespace nimbus
