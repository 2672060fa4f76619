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
  a.theta = std::atan2(k.x(), k.z());
  a.phi = -std::asin(std::clamp(k.y(), -1.0, 1.0));
  // phi' = -k_eta' / cos phi;  theta' = (k_zeta k_xi' - k_xi k_zeta') / (k_xi^2 + k_zeta^2).
  if (horizontal2 > 0.0) {
    a.phi_rate = -k_rate.y() / std::sqrt(horizontal2);
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

double tilt(double theta, double phi) {
  const double horizontal = std::hypot(std::sin(theta) * std::cos(phi), std::sin(phi));  // |(k_xi, k_eta)|
  return std::atan2(horizontal, std::cos(theta) * std::cos(phi));
}

double azimuth(double theta, double phi) {
  return std::atan2(-std::sin(phi), std::sin(theta) * std::cos(phi));  // atan2(k_eta, k_xi); atan2(0, 0) = 0
}

double ContinuousAzimuth::operator()(double theta, double phi) {
  const double k_xi = std::sin(theta) * std::cos(phi);
  const double k_eta = -std::sin(phi);
  if (k_xi == 0.0 && k_eta == 0.0) return previous_;  // vertical: no direction, keep the last one (0 at first)
  const double wrapped = std::atan2(k_eta, k_xi);
  if (!started_) {
    started_ = true;
    return previous_ = wrapped;
  }
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  return previous_ = wrapped + kTwoPi * std::round((previous_ - wrapped) / kTwoPi);
}

void insert_axis_direction_columns(Trajectory& part, ContinuousAzimuth& continuous) {
  std::vector<double> tilts(part.size()), azimuths(part.size());
  for (std::size_t i = 0; i < part.size(); ++i) {
    tilts[i] = tilt(part.theta[i], part.phi[i]);
    azimuths[i] = continuous(part.theta[i], part.phi[i]);
  }
  part.extra.insert(part.extra.begin(), {{std::string(kAxisDirectionColumns[0]), std::move(tilts)},
                                         {std::string(kAxisDirectionColumns[1]), std::move(azimuths)}});
}

}  // namespace heavytop
