#include "heavytop/frames.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Geometry>


namespace heavytop {

Eigen::Matrix3d axis_frame(double phi, double theta) {
  const Eigen::Matrix3d r_eta = Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix3d r_xi = Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return r_eta * r_xi;
}

Eigen::Vector3d axis_frame_rate(double /*phi*/, double theta, double phi_rate, double theta_rate) {
  return phi_rate * Eigen::Vector3d(std::cos(theta), 0.0, -std::sin(theta)) +
         theta_rate * Eigen::Vector3d::UnitY();
}

AxisAngles axis_angles(const Eigen::Vector3d& k, const Eigen::Vector3d& k_rate) {
  AxisAngles a;
  const double horizontal2 = k.x() * k.x() + k.z() * k.z();  // cos^2 phi
  const double cos_phi = std::sqrt(horizontal2);
  // theta = atan2(k_xi, k_zeta), by asin in its octant with the square root shared (frames.hpp)
  a.theta = horizontal2 > 1e-280 ? atan2_in_octant(k.x(), k.z(), cos_phi) : std::atan2(k.x(), k.z());
  a.phi = -std::asin(std::clamp(k.y(), -1.0, 1.0));
  // phi' = -k_eta' / cos phi;  theta' = (k_zeta k_xi' - k_xi k_zeta') / (k_xi^2 + k_zeta^2).
  if (horizontal2 > 0.0) {
    a.phi_rate = -k_rate.y() / cos_phi;
    a.theta_rate = (k.z() * k_rate.x() - k.x() * k_rate.z()) / horizontal2;
  }
  return a;
}

RigidBodyState initial_rigid_body_state(const InitialState& s) {
  RigidBodyState x;
  x.attitude = axis_frame(s.phi0, s.theta0);
  const Eigen::Vector3d omega_fixed =
      axis_frame_rate(s.phi0, s.theta0, s.phi_rate0, s.theta_rate0) + s.spin * x.attitude.col(2);
  x.omega = x.attitude.transpose() * omega_fixed;
  return x;
}

namespace {

// The horizontal components of k and its vertical one (SPEC section 2), from one sin and cos
// of each angle: (sin theta cos phi, -sin phi) and cos theta cos phi.
struct Axis {
  double xi, eta, zeta;
};
Axis axis_of(double theta, double phi) {
  const double sin_theta = std::sin(theta), cos_theta = std::cos(theta);
  const double sin_phi = std::sin(phi), cos_phi = std::cos(phi);
  return {sin_theta * cos_phi, -sin_phi, cos_theta * cos_phi};
}

double tilt_of(const Axis& k) { return tilt_of_axis(k.xi, k.eta, k.zeta); }

}  // namespace

double tilt(double theta, double phi) { return tilt_of(axis_of(theta, phi)); }

double azimuth(double theta, double phi) {
  const Axis k = axis_of(theta, phi);
  return azimuth_of_axis(k.xi, k.eta);
}

double ContinuousAzimuth::operator()(double theta, double phi) {
  const Axis k = axis_of(theta, phi);
  return of_axis(k.xi, k.eta);
}

double ContinuousAzimuth::of_axis(double k_xi, double k_eta) {
  if (k_xi == 0.0 && k_eta == 0.0) return previous_;  // vertical: no direction, keep the last one (0 at first)
  const double wrapped = azimuth_of_axis(k_xi, k_eta);
  if (!started_) {
    started_ = true;
    return previous_ = wrapped;
  }
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  // The last sample's multiple of 2 pi, while it brings this one within 3 rad of the last: then
  // (previous - wrapped) / 2 pi lies within 3 / (2 pi) = 0.48 of it and round() gives it too (the
  // same bits, without a division and round() a sample; a zero azimuth takes round()'s way,
  // for the sign of its zero).
  const double kept = wrapped + kTwoPi * turns_;
  if (std::abs(kept - previous_) < 3.0 && wrapped != 0.0) return previous_ = kept;
  turns_ = std::round((previous_ - wrapped) / kTwoPi);
  return previous_ = wrapped + kTwoPi * turns_;
}

void insert_axis_direction_columns(Trajectory& part, ContinuousAzimuth& continuous) {
  std::vector<double> tilts(part.size()), azimuths(part.size());
  for (std::size_t i = 0; i < part.size(); ++i) {
    const Axis k = axis_of(part.theta[i], part.phi[i]);  // once for both columns
    tilts[i] = tilt_of(k);
    azimuths[i] = continuous.of_axis(k.xi, k.eta);
  }
  part.extra.insert(part.extra.begin(), {{std::string(kAxisDirectionColumns[0]), std::move(tilts)},
                                         {std::string(kAxisDirectionColumns[1]), std::move(azimuths)}});
}

}  // namespace heavytop
