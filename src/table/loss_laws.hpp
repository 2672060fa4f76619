#pragma once
// Private to the library: the laws of a real top's losses (contact_losses.hpp), Hertz's patch
// and the air's torque on a spinning surface, templated on the scalar so that the table's
// equations differentiate them by the complex step; contact_losses.cpp's double functions are
// these.
#include <algorithm>
#include <cmath>
#include <complex>
#include <type_traits>

#include "heavytop/contact_losses.hpp"

namespace heavytop::detail {

inline double real_part(double x) { return x; }
inline double real_part(const std::complex<double>& x) { return x.real(); }

template <class T>
T cube_root(const T& x) {
  if constexpr (std::is_same_v<T, double>)
    return std::cbrt(x);
  else
    return real_part(x) > 0.0 ? std::pow(x, 1.0 / 3.0) : T(0.0);
}

// m: Hertz's patch radius a = (3 N R / (4 E*))^(1/3) of a sphere of radius R (m) pressed on a
// flat by `load` (N; 0 for a load <= 0) with contact modulus E* (Pa).
template <class T>
T hertz_radius(const T& load, double sphere_radius, double modulus) {
  if (!(real_part(load) > 0.0)) return T(0.0);
  return cube_root(T(3.0 * sphere_radius / (4.0 * modulus) * load));
}

// N m, with the sign of `spin`: the torque the air exerts against `surface` spinning at `spin`
// (rad/s) about its axis. |spin| is continued analytically as sqrt(spin^2) for the complex step.
template <class T>
T air_torque_of(const AirSurface& surface, const Air& air, const T& spin) {
  using std::pow;
  using std::sqrt;
  const T size = sqrt(spin * spin);
  if (real_part(size) == 0.0) return T(0.0);
  const double rho = air.density, mu = air.viscosity, nu = mu / rho, R = surface.radius;
  const T reynolds = size * (R * R / nu);
  switch (surface.kind) {
    case AirSurface::Kind::Face: {
      const double ri = surface.inner_radius;
      // Below Re = 3e5 von Karman's laminar layer (Cochran's 3.87 for a disc's two faces: a
      // quarter of C_M rho w^2 R^5 per face, the local shear growing as r); above, the turbulent
      // layer (0.146 Re^-1/5, the local shear as r^(8/5)).
      if (real_part(reynolds) < 3e5)
        return (3.87 / 4.0) * rho * std::sqrt(nu) * spin * sqrt(size) * (pow(R, 4) - pow(ri, 4));
      return (0.146 / 4.0) * rho * pow(nu, 0.2) * spin * pow(size, T(0.8)) * (pow(R, 4.6) - pow(ri, 4.6));
    }
    case AirSurface::Kind::Cylinder:  // the exact laminar flow: shear 2 mu w at the wall
      return 4.0 * 3.141592653589793 * mu * R * R * surface.length * spin;
    case AirSurface::Kind::Cone: {  // a face's laminar layer with w sin(alpha): 1 / sqrt(sin alpha) as large
      const double sin_alpha = R / std::hypot(R, surface.length);
      return (3.87 / 4.0) * rho * std::sqrt(nu) * spin * sqrt(size) * pow(R, 4) / std::sqrt(sin_alpha);
    }
    case AirSurface::Kind::Sphere: {  // Stokes below Re of about 10, Sawatzki above
      const T stokes = 16.0 * 3.141592653589793 / reynolds;
      const T sawatzki = 6.45 / sqrt(reynolds) + 32.1 / reynolds;
      const T coefficient = real_part(stokes) > real_part(sawatzki) ? stokes : sawatzki;
      return 0.5 * coefficient * rho * spin * size * pow(R, 5);
    }
  }
  return T(0.0);
}

}  // namespace heavytop::detail
