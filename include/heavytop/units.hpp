#pragma once
/// \file
/// Units people use beside SI (SPEC section 9): spins in revolutions per minute, angles in
/// degrees (typed as `--theta0-deg`, `theta0_deg`, ...; stored and computed in rad).

#include <numbers>

namespace heavytop {

/// rad/s per rpm: one revolution (2 pi rad) per minute (60 s).
inline constexpr double kRadPerSecondPerRpm = std::numbers::pi / 30.0;

/// rad/s of a spin given in rpm (the one conversion every reader of `spin_rpm` uses).
constexpr double rad_per_s_from_rpm(double rpm) noexcept { return rpm * kRadPerSecondPerRpm; }
/// rpm of a spin in rad/s.
constexpr double rpm_from_rad_per_s(double spin) noexcept { return spin / kRadPerSecondPerRpm; }

/// rad per degree: pi / 180.
inline constexpr double kRadPerDegree = std::numbers::pi / 180.0;

/// rad of an angle given in degrees (the one conversion every degree input uses; the same
/// product as Python's math.radians and NumPy's deg2rad, so 30 degrees is 0.5235987755982988
/// rad to the last bit).
constexpr double rad_from_degrees(double degrees) noexcept { return degrees * kRadPerDegree; }
/// degrees of an angle in rad.
constexpr double degrees_from_rad(double rad) noexcept { return rad / kRadPerDegree; }

}  // namespace heavytop
