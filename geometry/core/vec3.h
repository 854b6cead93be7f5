#pragma once
// Small fixed-size vector types used everywhere. World frame: metres, z up, x east, y north.
#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products

namespace skyband {

using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Vec2 = Eigen::Vector2d;

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace skyband
