// A body from its parts (SPEC section 10): each closed form against an independent route
// (Gauss quadrature over the solid in cylindrical coordinates), the polyhedral integrals
// against exact closed forms of boxes and prisms, the tessellated cylinder's order of
// convergence to the smooth one, and the refusals.
#include <cmath>
#include <numbers>

#include <boost/math/quadrature/gauss.hpp>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "heavytop/mass_properties.hpp"
#include "test_support.hpp"

// Parts are written with designated initializers, the fields not named keeping their defaults.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace heavytop {
namespace {

constexpr double pi = std::numbers::pi;

// The largest difference of mass, centre and tensor, each relative to its own scale.
double relative_difference(const MassProperties& a, const MassProperties& b) {
  const double size = std::sqrt(a.inertia.trace() / (2 * a.mass));
  return std::max({std::abs(a.mass - b.mass) / a.mass, (a.centre - b.centre).norm() / size,
                   (a.inertia - b.inertia).cwiseAbs().maxCoeff() / a.inertia.trace()});
}

// Mass properties of a solid of revolution by quadrature: rho over z in [z_lo, z_hi], r in
// [r_in(z), r_out(z)], the azimuth by the trapezoidal rule (exact for the trigonometric
// polynomials of degree < 8 the integrand has); Gauss-Legendre with 12 points is exact for
// the polynomials in r and z (degree <= 7) of every shape here.
template <class Inner, class Outer>
MassProperties by_quadrature(double rho, double z_lo, double z_hi, Inner r_in, Outer r_out) {
  using Gauss = boost::math::quadrature::gauss<double, 12>;
  MassProperties p;
  double m = 0;
  Eigen::Vector3d first = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();  // integral of p p^T dm
  constexpr int kAzimuths = 8;
  for (int k = 0; k < kAzimuths; ++k) {
    const double phi = 2 * pi * k / kAzimuths, c = std::cos(phi), s = std::sin(phi);
    auto moment = [&](auto f) {
      return Gauss::integrate(
                 [&](double z) {
                   return Gauss::integrate([&](double r) { return rho * r * f(Eigen::Vector3d(r * c, r * s, z)); },
                                           r_in(z), r_out(z));
                 },
                 z_lo, z_hi) *
             (2 * pi / kAzimuths);
    };
    m += moment([](const Eigen::Vector3d&) { return 1.0; });
    for (int i = 0; i < 3; ++i) {
      first(i) += moment([i](const Eigen::Vector3d& x) { return x(i); });
      for (int j = 0; j < 3; ++j) second(i, j) += moment([i, j](const Eigen::Vector3d& x) { return x(i) * x(j); });
    }
  }
  p.mass = m;
  p.centre = first / m;
  p.inertia = second.trace() * Eigen::Matrix3d::Identity() - second;
  return p;
}

TEST(SolidParts, ClosedFormsMatchQuadratureOverTheSolid) {
  const double rho = 7800.0, a = 0.02, b = 0.012, h = 0.035;
  for (const double z0 : {0.0, 0.013, -0.05}) {
    auto zero = [](double) { return 0.0; };
    struct Case {
      SolidPart part;
      MassProperties expected;
    };
    std::vector<Case> cases;
    SolidPart p{.radius = a, .height = h, .z0 = z0, .density = rho};
    p.shape = PartShape::Cylinder;
    cases.push_back({p, by_quadrature(rho, z0, z0 + h, zero, [&](double) { return a; })});
    p.shape = PartShape::Tube;
    p.inner_radius = b;
    cases.push_back({p, by_quadrature(rho, z0, z0 + h, [&](double) { return b; }, [&](double) { return a; })});
    p.inner_radius = 0.0;
    p.shape = PartShape::Cone;
    cases.push_back({p, by_quadrature(rho, z0, z0 + h, zero, [&](double z) { return a * (z - z0) / h; })});
    p.apex_up = true;
    cases.push_back({p, by_quadrature(rho, z0, z0 + h, zero, [&](double z) { return a * (1 - (z - z0) / h); })});
    // The sphere: SphereMatchesQuadratureInSphericalCoordinates (its profile is a square root).
    for (const auto& c : cases) {
      const MassProperties closed = mass_properties(c.part, "body.part[0]");
      EXPECT_LT(relative_difference(closed, c.expected), 1e-12) << name(c.part.shape) << " z0 " << z0;
      // Given by mass instead of density: the same body.
      SolidPart by_mass = c.part;
      by_mass.density.reset();
      by_mass.mass = closed.mass;
      EXPECT_LT(relative_difference(mass_properties(by_mass, "k"), closed), 1e-15) << name(c.part.shape);
    }
  }
}

// The sphere exactly: Gauss-Legendre over the cube of the ball in spherical coordinates,
// exact for its polynomial integrand (r^2 sin(t) times a polynomial in r, cos, sin).
TEST(SolidParts, SphereMatchesQuadratureInSphericalCoordinates) {
  using Gauss = boost::math::quadrature::gauss<double, 20>;
  const double rho = 1200.0, a = 0.03, z0 = -0.01, zc = z0 + a;
  auto integral = [&](auto f) {  // f(x, y, z), integrated over the ball by (r, t, azimuth)
    double total = 0.0;
    constexpr int kAz = 8;
    for (int k = 0; k < kAz; ++k) {
      const double p = 2 * pi * k / kAz;
      total += Gauss::integrate([&](double r) {
        return Gauss::integrate([&](double t) {
          const double x = r * std::sin(t) * std::cos(p), y = r * std::sin(t) * std::sin(p), z = zc + r * std::cos(t);
          return rho * f(x, y, z) * r * r * std::sin(t);
        }, 0.0, pi);
      }, 0.0, a) * 2 * pi / kAz;
    }
    return total;
  };
  const MassProperties s = mass_properties(SolidPart{.shape = PartShape::Sphere, .radius = a, .z0 = z0, .density = rho}, "k");
  const double m = integral([](double, double, double) { return 1.0; });
  const double C = integral([](double x, double y, double) { return x * x + y * y; });
  const double A = integral([](double, double y, double z) { return y * y + z * z; });
  const double mz = integral([](double, double, double z) { return z; });
  // sin(t) is not a polynomial: Gauss-Legendre with 20 points is exact to rounding anyway
  // (its error there is far below 1e-16).
  EXPECT_NEAR(s.mass / m, 1.0, 1e-13);
  EXPECT_NEAR(s.inertia(2, 2) / C, 1.0, 1e-13);
  EXPECT_NEAR(s.inertia(0, 0) / A, 1.0, 1e-13);
  EXPECT_NEAR(s.centre.z() / (mz / m), 1.0, 1e-13);
}

TEST(SolidParts, TextbookValues) {
  // C = m a^2 / 2 (cylinder), 3 m a^2 / 10 (cone), 2 m a^2 / 5 (sphere); a cone's tip to its
  // centroid is 3 h / 4; a thin disc of mass m at height l: A = m a^2 / 4 + m l^2.
  const double a = 0.025;
  const auto cone = mass_properties(SolidPart{.shape = PartShape::Cone, .radius = a, .height = 0.04, .mass = 0.1}, "k");
  EXPECT_NEAR(cone.inertia(2, 2), 0.3 * 0.1 * a * a, 1e-18);
  EXPECT_NEAR(cone.centre.z(), 0.03, 1e-17);
  // The top of Usubamatov, Math. Probl. Eng. 2018, 6132891, Table 2: a 20 g disc of radius
  // 25 mm, 20 mm above the support: 0.625e-5 about the axis, 1.1125e-5 about the support's
  // transverse axes (a disc 0.1 mm thick here: its thickness adds m h^2 / 12 ~ 2e-11).
  const double h = 1e-4;
  const auto disc = mass_properties(
      SolidPart{.shape = PartShape::Cylinder, .radius = a, .height = h, .z0 = 0.02 - h / 2, .mass = 0.02}, "k");
  EXPECT_NEAR(disc.inertia(2, 2), 0.625e-5, 1e-18);
  EXPECT_NEAR(disc.inertia(0, 0), 1.1125e-5, 2e-11);
}

// ---- meshes -------------------------------------------------------------------------------

// An axis-aligned box as 12 outward triangles.
TriangleMesh box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  TriangleMesh m;
  for (int i = 0; i < 8; ++i)
    m.vertices.emplace_back(i & 1 ? hi.x() : lo.x(), i & 2 ? hi.y() : lo.y(), i & 4 ? hi.z() : lo.z());
  const std::uint32_t quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

// A right prism on a regular n-gon inscribed in radius a, from z0 to z0 + h, vertices shared.
TriangleMesh prism(int n, double a, double h, double z0) {
  TriangleMesh m;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * pi * k / n;
    m.vertices.emplace_back(a * std::cos(t), a * std::sin(t), z0);
    m.vertices.emplace_back(a * std::cos(t), a * std::sin(t), z0 + h);
  }
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(0, 0, z0);
  m.vertices.emplace_back(0, 0, z0 + h);
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(n); ++k) {
    const std::uint32_t j = (k + 1) % n;
    m.triangles.push_back({2 * k, 2 * j, 2 * j + 1});
    m.triangles.push_back({2 * k, 2 * j + 1, 2 * k + 1});
    m.triangles.push_back({bottom, 2 * j, 2 * k});
    m.triangles.push_back({bottom + 1, 2 * k + 1, 2 * j + 1});
  }
  return m;
}

TEST(Meshes, BoxGivesItsExactMassProperties) {
  const Eigen::Vector3d lo(0.01, -0.02, -0.005), hi(0.05, 0.01, 0.03);
  const double rho = 2700.0;
  const MassProperties p = mass_properties(box(lo, hi), rho, std::nullopt, "body.part[0]");
  // Closed forms: integral of x^i y^j z^k over the box is a product of one-dimensional ones.
  auto I1 = [&](int d, int power) { return (std::pow(hi(d), power + 1) - std::pow(lo(d), power + 1)) / (power + 1); };
  auto moment = [&](int px, int py, int pz) { return rho * I1(0, px) * I1(1, py) * I1(2, pz); };
  const double m = moment(0, 0, 0);
  MassProperties e;
  e.mass = m;
  e.centre = Eigen::Vector3d(moment(1, 0, 0), moment(0, 1, 0), moment(0, 0, 1)) / m;
  const double xx = moment(2, 0, 0), yy = moment(0, 2, 0), zz = moment(0, 0, 2);
  const double xy = moment(1, 1, 0), xz = moment(1, 0, 1), yz = moment(0, 1, 1);
  e.inertia << yy + zz, -xy, -xz, -xy, xx + zz, -yz, -xz, -yz, xx + yy;
  EXPECT_LT(relative_difference(p, e), 1e-12);
  // By mass: the same with rho = mass / volume.
  EXPECT_LT(relative_difference(mass_properties(box(lo, hi), std::nullopt, m, "k"), e), 1e-12);
  // Inside out (every triangle reversed): the same solid.
  TriangleMesh flipped = box(lo, hi);
  for (auto& t : flipped.triangles) std::swap(t[1], t[2]);
  EXPECT_LT(relative_difference(mass_properties(flipped, rho, std::nullopt, "k"), e), 1e-12);
}

// A regular n-gon of circumradius a: area (n/2) a^2 sin(2 pi / n); polar moment
// (n a^4 / 12) sin(2 pi / n) (2 + cos(2 pi / n)), half of it about each diameter.
MassProperties exact_prism(int n, double a, double h, double z0, double rho) {
  const double t = 2 * pi / n, area = 0.5 * n * a * a * std::sin(t);
  const double polar = n * std::pow(a, 4) / 12 * std::sin(t) * (2 + std::cos(t));
  MassProperties p;
  p.mass = rho * area * h;
  const double zc = z0 + h / 2;
  p.centre = {0, 0, zc};
  const double transverse = rho * h * polar / 2 + p.mass * (h * h / 12 + zc * zc);
  p.inertia.diagonal() << transverse, transverse, rho * h * polar;
  return p;
}

TEST(Meshes, PrismGivesItsExactPolygonalMassProperties) {
  for (const int n : {3, 4, 7, 64, 1000}) {
    const auto p = mass_properties(prism(n, 0.02, 0.01, 0.004), 1000.0, std::nullopt, "k");
    EXPECT_LT(relative_difference(p, exact_prism(n, 0.02, 0.01, 0.004, 1000.0)), 1e-12) << n;
  }
}

TEST(Meshes, TessellatedCylinderConvergesAtSecondOrder) {
  const double a = 0.02, h = 0.01, z0 = 0.004, rho = 1000.0;
  const auto smooth = mass_properties(SolidPart{.radius = a, .height = h, .z0 = z0, .density = rho}, "k");
  std::vector<double> errors;
  for (int n = 16; n <= 512; n *= 2) {
    const auto p = mass_properties(prism(n, a, h, z0), rho, std::nullopt, "k");
    errors.push_back(std::abs(p.inertia(2, 2) - smooth.inertia(2, 2)) / smooth.inertia(2, 2));
  }
  // The error is c2 / n^2 + c4 / n^4 (1 - C_n / C = (2 pi / n)^2 / 3 + ...): the measured
  // order approaches 2 from below, its distance shrinking fourfold per doubling.
  double last_gap = 1.0;
  for (std::size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    const double gap = std::abs(order - 2.0);
    EXPECT_LT(gap, 0.03) << "facets " << (16 << i);
    EXPECT_NEAR(last_gap / gap, 4.0, i == 1 ? 1e9 : 0.1) << "facets " << (16 << i);
    last_gap = gap;
  }
  EXPECT_NEAR(std::log2(errors[errors.size() - 2] / errors.back()), 2.0, 1e-4);
  // The leading term exactly: 1 - C_n / C -> (2 pi / n)^2 / 3.
  EXPECT_NEAR(errors.back() / (std::pow(2 * pi / 512, 2) / 3), 1.0, 1e-4);
  ::testing::Test::RecordProperty("order_C_512_facets", test_support::sci(std::log2(errors[errors.size() - 2] / errors.back())));
}

TEST(Meshes, OpenOrMisorientedMeshIsRefusedNamingThePartAndTheCount) {
  TriangleMesh open = box({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  EXPECT_EQ(mesh_defects(open).open_edges, 3u);
  try {
    mass_properties(open, 1.0, std::nullopt, "body.part[1] (top.stl)");
    FAIL() << "accepted an open mesh";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.part[1] (top.stl)");
    EXPECT_NE(e.rule().find("3 open edges"), std::string::npos) << e.rule();
  }
  TriangleMesh flipped = box({0, 0, 0}, {1, 1, 1});
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_EQ(mesh_defects(flipped).misoriented_edges, 3u);
  EXPECT_THROW(mass_properties(flipped, 1.0, std::nullopt, "k"), InvalidInput);
  // An STL-like soup (every triangle its own vertices) is welded: closed.
  TriangleMesh soup;
  const TriangleMesh b = box({0, 0, 0}, {1, 2, 3});
  for (const auto& t : b.triangles) {
    const auto base = static_cast<std::uint32_t>(soup.vertices.size());
    for (auto i : t) soup.vertices.push_back(b.vertices[i]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(mesh_defects(soup).ok());
  EXPECT_NEAR(mass_properties(soup, 1.0, std::nullopt, "k").mass, 6.0, 1e-14);
}

TEST(Parts, BadPartsAreRefusedNamingTheKey) {
  auto key_of = [](SolidPart p) {
    try {
      mass_properties(p, "body.part[2]");
    } catch (const InvalidInput& e) {
      return e.key();
    }
    return std::string("accepted");
  };
  EXPECT_EQ(key_of({.radius = -1, .height = 1, .density = 1}), "body.part[2].radius");
  EXPECT_EQ(key_of({.radius = 1, .height = 0, .density = 1}), "body.part[2].height");
  EXPECT_EQ(key_of({.radius = 1, .height = 1, .density = 1, .mass = 1}), "body.part[2].mass");
  EXPECT_EQ(key_of({.radius = 1, .height = 1}), "body.part[2].density");
  EXPECT_EQ(key_of({.shape = PartShape::Tube, .radius = 1, .inner_radius = 1, .height = 1, .density = 1}),
            "body.part[2].inner_radius");
  EXPECT_EQ(key_of({.radius = 1, .height = 1, .density = std::nan("")}), "body.part[2].density");
}

// ---- the assembled body ---------------------------------------------------------------------

TEST(Assembly, PartsAddAndGiveTheBody) {
  // A cone (tip at O) under a cylinder: the sum of the parts' own closed forms.
  const SolidPart cone{.shape = PartShape::Cone, .radius = 0.02, .height = 0.02, .density = 700};
  const SolidPart disc{.radius = 0.02, .height = 0.005, .z0 = 0.02, .density = 700};
  const auto pc = mass_properties(cone, "a"), pd = mass_properties(disc, "b");
  const BodyAssembly a = assemble({pc, pd});
  EXPECT_FALSE(a.general());
  const Body b = body_of(a, 9.81, {"body.part[0] (cone)", "body.part[1] (cylinder)"});
  EXPECT_DOUBLE_EQ(b.mass, pc.mass + pd.mass);
  EXPECT_NEAR(b.length, (pc.mass * pc.centre.z() + pd.mass * pd.centre.z()) / b.mass, 1e-17);
  EXPECT_DOUBLE_EQ(b.C, pc.inertia(2, 2) + pd.inertia(2, 2));
  EXPECT_DOUBLE_EQ(b.A, b.B);
  EXPECT_NO_THROW(validate(b));
}

TEST(Assembly, ProductsAndOffsetAreReportedAndRefused) {
  // A cylinder tilted by beta about x, then a box off the axis: the principal axis is beta
  // from z, and the box's offset and products are those of its closed form.
  const double beta = 0.1;
  TriangleMesh cyl = prism(256, 0.02, 0.1, 0.0);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(beta, Eigen::Vector3d::UnitX()).toRotationMatrix();
  for (auto& v : cyl.vertices) v = R * v;
  const BodyAssembly tilted = assemble({mass_properties(cyl, 1000.0, std::nullopt, "k")});
  EXPECT_TRUE(tilted.general());
  EXPECT_EQ(tilted.Ixy, 0.0);
  EXPECT_NE(tilted.Iyz, 0.0);
  EXPECT_NEAR(tilted.principal_tilt, beta, 1e-12);
  const auto on_axis = mass_properties(SolidPart{.radius = 0.02, .height = 0.01, .density = 1000}, "k");
  const auto off = mass_properties(box({0.01, 0.0, 0.0}, {0.012, 0.003, 0.01}), 1000.0, std::nullopt, "k");
  const BodyAssembly a = assemble({on_axis, off});
  EXPECT_EQ(a.main_part, 1u);
  EXPECT_NEAR(a.offset_x, off.mass * off.centre.x() / (on_axis.mass + off.mass), 1e-17);
  EXPECT_NEAR(a.Ixy, off.mass * off.centre.x() * off.centre.y(), 1e-16);  // the box's x y moment
  try {
    body_of(a, 9.81, {"body.part[0] (cylinder)", "body.part[1] (lump.stl)"});
    FAIL() << "a general body became a Body";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.part[1] (lump.stl)");
    EXPECT_NE(e.rule().find("integrated by `simulate --model nonlinear` only"), std::string::npos);
  }
  // Below 1e-9 of the body's size: zero. A box centred 1e-12 m off the axis.
  const double d = 1e-12;
  const BodyAssembly tiny = assemble({mass_properties(box({-0.01 + d, -0.01, 0}, {0.01 + d, 0.01, 0.02}), 1.0, std::nullopt, "k")});
  EXPECT_FALSE(tiny.general());
}

// Where another part reaches the table (SPEC 16: on a table a body of parts "falls" there): a
// cone tip under a wider disc touches at the disc's lower rim, closed form
// R2 sin(theta) - h cos(theta) = r, theta = atan2(h, R2) + asin(r / hypot(h, R2)).
TEST(Parts, TouchTiltIsWhereTheWidestRimReachesTheTable) {
  const double h = 0.03, R2 = 0.035;
  const std::vector<SolidPart> top = {
      {.shape = PartShape::Cone, .radius = 0.01, .height = h, .z0 = 0.0, .density = 700.0},
      {.shape = PartShape::Cylinder, .radius = R2, .height = 0.008, .z0 = h, .density = 700.0},
  };
  for (const double r : {0.0, 0.002}) {
    const std::optional<double> touch = touch_tilt(top, r, 0.0);
    ASSERT_TRUE(touch);
    EXPECT_NEAR(*touch, std::atan2(h, R2) + std::asin(r / std::hypot(h, R2)), 1e-11) << r;
  }
  // A ball on its own never touches with anything else; a ball with a stem above touches with
  // the stem's top rim before upside down (a tippe top's stem, issue 43's second contact).
  const std::vector<SolidPart> ball = {{.shape = PartShape::Sphere, .radius = 0.015, .z0 = -0.015, .density = 1000.0}};
  EXPECT_FALSE(touch_tilt(ball, 0.015, 0.0));
  std::vector<SolidPart> tippe = ball;
  tippe.push_back({.shape = PartShape::Cylinder, .radius = 0.004, .height = 0.01, .z0 = 0.012, .density = 1000.0});
  const std::optional<double> stem = touch_tilt(tippe, 0.015, 0.0);
  ASSERT_TRUE(stem);
  // The stem's top rim (z 0.022, radius 0.004) reaches it: 0.015 + R cos(theta + atan2(a, z)) = 0.
  const double z = 0.022, a = 0.004, R = std::hypot(z, a);
  EXPECT_NEAR(*stem, std::acos(-0.015 / R) - std::atan2(a, z), 1e-11);
  // A part below the tip with the body upright: refused naming it.
  const std::vector<SolidPart> sunk = {{.shape = PartShape::Cylinder, .radius = 0.01, .height = 0.01, .z0 = -0.02,
                                        .density = 1000.0}};
  try {
    touch_tilt(sunk, 0.005, 0.0);
    FAIL() << "not refused";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(e.key(), "body.part[0]");
  }
}

}  // namespace
}  // namespace heavytop
