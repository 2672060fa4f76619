#include "heavytop/frames.hpp"

#include <algorithm>
#include <cmath>

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
  return std::acos(std::clamp(std::cos(theta) * std::cos(phi), -1.0, 1.0));
}

}  // namespace heavytop
