#pragma once
// Vector types used everywhere. 2D scenes use Vec3 with z = 0 and stay exactly planar,
// because every force in a planar scene has a zero z component.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products (normals, areas, volumes)

namespace springlab {

using Vec3 = Eigen::Vector3d;

}  // namespace springlab
