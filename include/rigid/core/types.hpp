#pragma once
/// Basic numeric types and physical constants shared by every module (SI units throughout).
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace rigid {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

/// Standard gravity (unit: m/s^2). The study's table uses g = 980.665 cm/s^2 (physics.md §1).
inline constexpr double kGravity = 9.80665;
inline constexpr double kPi = 3.14159265358979323846;

}  // namespace rigid
