#pragma once
/// \file
/// Units people use beside SI (SPEC section 9): spins in revolutions per minute.

#include <numbers>

namespace heavytop {

/// rad/s per rpm: one revolution (2 pi rad) per minute (60 s).
inline constexpr double kRadPerSecondPerRpm = std::numbers::pi / 30.0;

/// rad/s of a spin given in rpm (the one conversion every reader of `spin_rpm` uses).
constexpr double rad_per_s_from_rpm(double rpm) noexcept { return rpm * kRadPerSecondPerRpm; }
/// rpm of a spin in rad/s.
constexpr double rpm_from_rad_per_s(double spin) noexcept { return spin / kRadPerSecondPerRpm; }

}  // namespace heavytop
