#pragma once
/// \file
/// Frames and the paper's small angles, exactly as SPEC section 2 defines them.
/// Fixed frame (xi, eta, zeta), zeta up; k is the unit vector of the body's spin axis.

#include <array>
#include <cmath>
#include <string_view>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "heavytop/state.hpp"

namespace heavytop {

/// theta, phi and their rates of the axis k (all rad or rad/s).
struct AxisAngles {
  double theta = 0.0;       ///< rad, atan2(k_xi, k_zeta)
  double phi = 0.0;         ///< rad, -asin(k_eta)
  double theta_rate = 0.0;  ///< rad/s
  double phi_rate = 0.0;    ///< rad/s
};

/// The axis frame Q(phi, theta) = R_eta(theta) R_xi(phi) (fixed-frame components of the
/// paper's Oxyz axes, as columns; not spinning with the body). Its third column is k.
Eigen::Matrix3d axis_frame(double phi, double theta);

/// Fixed-frame angular velocity of the axis frame: phi' (cos theta, 0, -sin theta) + theta' (0,1,0).
Eigen::Vector3d axis_frame_rate(double phi, double theta, double phi_rate, double theta_rate);

/// theta, phi of a unit axis k and their rates from k' (fixed-frame components, 1/s).
/// Exact inverse of k = (sin theta cos phi, -sin phi, cos theta cos phi).
AxisAngles axis_angles(const Eigen::Vector3d& k, const Eigen::Vector3d& k_rate);

/// rad, in [0, pi]: the tilt of the axis from the upward vertical, acos(k_zeta) = acos(cos theta
/// cos phi) (SPEC section 2), computed as atan2(|k_perp|, k_zeta) so that it keeps full relative
/// precision near the vertical, where acos loses half the digits.
double tilt(double theta, double phi);

/// rad, in [0, pi]: tilt() of the axis k itself, the angle between k and the upward vertical
/// (k's fixed-frame components, of any length: dimensionless): what every tilt in heavytop is
/// computed by. Below 45 degrees asin(sqrt(h / (h + k_zeta^2))), h = k_xi^2 + k_eta^2 (a
/// third of atan2's time here, and as precise: asin's condition there is at most 1.27);
/// elsewhere, and where h is near underflow, atan2(hypot(k_xi, k_eta), k_zeta). The batch's
/// tilt (integrators/batch/batch_kernel.hpp) is the same expression.
inline double tilt_of_axis(double k_xi, double k_eta, double k_zeta) {
  const double h = k_xi * k_xi + k_eta * k_eta, v = k_zeta * k_zeta;
  if (k_zeta > 0.0 && h < v && h > 1e-280) return std::asin(std::sqrt(h / (h + v)));
  return std::atan2(std::hypot(k_xi, k_eta), k_zeta);
}

/// rad, in (-pi, pi]: the direction the axis leans to, atan2(k_eta, k_xi) (0 for a vertical axis).
double azimuth(double theta, double phi);

/// rad, in (-pi, pi]: atan2(y, x) given r = |(x, y)| > 0 (which its callers need anyway), as
/// asin of the smaller component over r placed in its octant: half of atan2's time, and as
/// precise (asin's argument is at most 1/sqrt(2), its condition at most 1.27, the tilt's rule);
/// pi, not -pi, for x < 0 and a zero y of either sign. The angles of axis_angles() and
/// azimuth_of_axis() (r from underflow's edge up: they take atan2 below 1e-140).
inline double atan2_in_octant(double y, double x, double r) {
  constexpr double kPi = 3.141592653589793, kHalfPi = 1.5707963267948966;
  if (std::abs(y) <= std::abs(x)) {
    const double a = std::asin(y / r);  // in [-pi/4, pi/4]
    return x > 0.0 ? a : (y < 0.0 ? -kPi - a : kPi - a);
  }
  const double b = std::asin(x / r);
  return y > 0.0 ? kHalfPi - b : b - kHalfPi;
}

/// rad, in (-pi, pi]: azimuth() of the axis k from its horizontal components (of any length:
/// dimensionless), atan2(k_eta, k_xi) by atan2_in_octant; 0 for (0, 0), and pi, not -pi, on
/// the negative xi axis whatever the sign of a zero k_eta.
inline double azimuth_of_axis(double k_xi, double k_eta) {
  const double h = k_xi * k_xi + k_eta * k_eta;
  if (!(h > 1e-280)) return k_xi == 0.0 && k_eta == 0.0 ? 0.0 : std::atan2(k_eta, k_xi);
  return atan2_in_octant(k_eta, k_xi, std::sqrt(h));
}

/// The people's columns of every trajectory (SPEC section 2): they follow SPEC's five, in
/// this order, in every simulate output.
inline constexpr std::array<std::string_view, 2> kAxisDirectionColumns = {"tilt", "azimuth"};

/// The azimuth made continuous in time, sample after sample (SPEC section 2): the first sample
/// is azimuth(theta, phi) in (-pi, pi] (0 for a vertical axis); each later one differs from
/// azimuth(theta, phi) by the multiple of 2 pi that brings it within pi of the previous sample;
/// while the axis is exactly vertical (tilt 0, no direction) it keeps the previous value.
class ContinuousAzimuth {
 public:
  /// rad, the next sample's continuous azimuth.
  double operator()(double theta, double phi);
  /// rad, the same from the axis' horizontal components k_xi = sin theta cos phi and
  /// k_eta = -sin phi (dimensionless).
  double of_axis(double k_xi, double k_eta);

 private:
  double previous_ = 0.0;
  double turns_ = 0.0;  // the multiple of 2 pi previous_ was given
  bool started_ = false;
};

/// Inserts the columns kAxisDirectionColumns (tilt, azimuth; rad) at the front of `part.extra`,
/// computed from its theta and phi, the azimuth continued from `azimuth`'s previous samples
/// (consecutive pieces of one trajectory share one ContinuousAzimuth).
void insert_axis_direction_columns(Trajectory& part, ContinuousAzimuth& azimuth);

/// The body's attitude and angular velocity at t = 0 for `linearized` and `nonlinear`
/// (SPEC section 2): principal axes x, y, z are the columns of Q(phi0, theta0) (psi = 0),
/// angular velocity phi_rate0 (cos theta0, 0, -sin theta0) + theta_rate0 (0, 1, 0) + spin k0.
struct RigidBodyState {
  Eigen::Matrix3d attitude;  ///< body-to-fixed rotation: columns are the body axes x, y, z
  Eigen::Vector3d omega;     ///< rad/s, angular velocity in body axes
};
RigidBodyState initial_rigid_body_state(const InitialState& state);

}  // namespace heavytop
