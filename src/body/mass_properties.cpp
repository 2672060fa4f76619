#include "heavytop/mass_properties.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <tuple>

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

namespace heavytop {

MassProperties& MassProperties::operator+=(const MassProperties& other) {
  const double m = mass + other.mass;
  centre = m > 0.0 ? Eigen::Vector3d((mass * centre + other.mass * other.centre) / m) : Eigen::Vector3d::Zero();
  mass = m;
  inertia += other.inertia;
  return *this;
}

const char* name(PartShape shape) noexcept {
  switch (shape) {
    case PartShape::Cylinder: return "cylinder";
    case PartShape::Tube: return "tube";
    case PartShape::Cone: return "cone";
    case PartShape::Sphere: return "sphere";
  }
  return "?";
}

std::optional<PartShape> part_shape_from_name(const std::string& text) noexcept {
  for (PartShape s : {PartShape::Cylinder, PartShape::Tube, PartShape::Cone, PartShape::Sphere})
    if (text == name(s)) return s;
  return std::nullopt;
}

namespace {

void require_positive(double value, const std::string& key) {
  if (!(std::isfinite(value) && value > 0.0)) throw InvalidInput(key, "must be a finite number > 0");
}

void validate_amount(std::optional<double> density, std::optional<double> mass, const std::string& key) {
  if (density && mass) throw InvalidInput(key + ".mass", "give density or mass, not both");
  if (!density && !mass) throw InvalidInput(key + ".density", "is required (or give mass)");
  if (density) require_positive(*density, key + ".density");
  if (mass) require_positive(*mass, key + ".mass");
}

// A solid of revolution by four numbers (docs/mass-properties.md): its volume, its centroid's
// height above its lowest point, its variance along z about the centroid and its mean r^2
// (r the distance from the axis), each per unit mass where it is a moment.
struct Revolution {
  double volume;    // m^3
  double centroid;  // m, above the lowest point
  double var_z;     // m^2, integral of (z - z_c)^2 dm / m
  double mean_r2;   // m^2, integral of r^2 dm / m (C = m mean_r2)
};

Revolution revolution(const SolidPart& p) {
  constexpr double pi = std::numbers::pi;
  const double a = p.radius, h = p.height;
  switch (p.shape) {
    case PartShape::Cylinder: return {pi * a * a * h, h / 2, h * h / 12, a * a / 2};
    case PartShape::Tube: {
      const double b = p.inner_radius;
      return {pi * (a - b) * (a + b) * h, h / 2, h * h / 12, (a * a + b * b) / 2};
    }
    case PartShape::Cone: return {pi * a * a * h / 3, p.apex_up ? h / 4 : 3 * h / 4, 3 * h * h / 80, 3 * a * a / 10};
    case PartShape::Sphere: return {4 * pi * a * a * a / 3, a, a * a / 5, 2 * a * a / 5};
  }
  return {};
}

}  // namespace

void validate(const SolidPart& part, const std::string& key) {
  require_positive(part.radius, key + ".radius");
  if (part.shape != PartShape::Sphere) require_positive(part.height, key + ".height");
  if (part.shape == PartShape::Tube &&
      !(std::isfinite(part.inner_radius) && part.inner_radius >= 0.0 && part.inner_radius < part.radius))
    throw InvalidInput(key + ".inner_radius", "must be a finite number in [0, radius)");
  if (!std::isfinite(part.z0)) throw InvalidInput(key + ".z0", "must be a finite number");
  validate_amount(part.density, part.mass, key);
}

MassProperties mass_properties(const SolidPart& part, const std::string& key) {
  validate(part, key);
  const Revolution r = revolution(part);
  MassProperties p;
  p.mass = part.mass ? *part.mass : *part.density * r.volume;
  const double zc = part.z0 + r.centroid;
  p.centre = {0.0, 0.0, zc};
  // About O: x^2 and y^2 each average r^2 / 2 over the circle; z^2 = var_z + z_c^2 (parallel axes).
  const double transverse = p.mass * (r.mean_r2 / 2 + r.var_z + zc * zc);
  p.inertia.diagonal() << transverse, transverse, p.mass * r.mean_r2;
  if (!std::isfinite(p.mass) || !p.inertia.allFinite())
    throw InvalidInput(key, "its mass or moments of inertia overflow a double");
  return p;
}

MeshDefects mesh_defects(const TriangleMesh& mesh) {
  MeshDefects d;
  // Vertices merged by exact position (STL repeats them per triangle, bit for bit): sorted by
  // their coordinates, equal runs share an id. Sorting beats a tree or a hash here.
  const std::size_t nv = mesh.vertices.size();
  std::vector<std::uint32_t> order(nv), id(nv);
  for (std::size_t i = 0; i < nv; ++i) order[i] = static_cast<std::uint32_t>(i);
  auto key = [&](std::uint32_t i) {
    const auto& v = mesh.vertices[i];
    return std::tuple(v.x(), v.y(), v.z());
  };
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return key(a) < key(b); });
  for (std::size_t r = 0, next = 0; r < nv; ++r) {
    if (r > 0 && key(order[r]) != key(order[r - 1])) ++next;
    id[order[r]] = static_cast<std::uint32_t>(next);
  }
  // Each directed edge as (low, high, runs low -> high?), sorted: an undirected edge's uses are
  // then one run, which must be exactly one of each direction.
  struct Edge {
    std::uint32_t lo, hi;
    bool up;
    bool operator<(const Edge& o) const { return std::tie(lo, hi, up) < std::tie(o.lo, o.hi, o.up); }
  };
  std::vector<Edge> edges;
  edges.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles) {
    if (t[0] >= nv || t[1] >= nv || t[2] >= nv) {
      ++d.degenerate_triangles;
      continue;
    }
    const std::uint32_t v[3] = {id[t[0]], id[t[1]], id[t[2]]};
    if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) {
      ++d.degenerate_triangles;
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = v[k], b = v[(k + 1) % 3];
      edges.push_back({std::min(a, b), std::max(a, b), a < b});
    }
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i, up = 0;
    for (; j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi; ++j) up += edges[j].up;
    const std::size_t total = j - i;
    if (total == 1) ++d.open_edges;
    else if (total > 2) ++d.nonmanifold_edges;
    else if (up != 1) ++d.misoriented_edges;
    i = j;
  }
  return d;
}

MassProperties mass_properties(const TriangleMesh& mesh, std::optional<double> density, std::optional<double> mass,
                               const std::string& key) {
  validate_amount(density, mass, key);
  if (mesh.triangles.empty()) throw InvalidInput(key, "the mesh has no triangles");
  const MeshDefects d = mesh_defects(mesh);
  if (!d.ok()) {
    std::string what;
    auto add = [&](std::size_t n, const char* one, const char* many) {
      if (n) what += fmt::format("{}{} {}", what.empty() ? "" : ", ", n, n == 1 ? one : many);
    };
    add(d.open_edges, "open edge", "open edges");
    add(d.misoriented_edges, "edge whose triangles are oriented inconsistently",
        "edges whose triangles are oriented inconsistently");
    add(d.nonmanifold_edges, "edge shared by more than two triangles", "edges shared by more than two triangles");
    add(d.degenerate_triangles, "degenerate triangle", "degenerate triangles");
    throw InvalidInput(key, fmt::format("the mesh is not the closed, consistently oriented surface of a solid: {}", what));
  }
  // Eberly's subexpressions: for each triangle, the integrals of 1, x, y, z, x^2, y^2, z^2,
  // xy, yz, zx over the solid as sums over its surface (the divergence theorem).
  auto sub = [](double w0, double w1, double w2, double& f1, double& f2, double& f3, double& g0, double& g1,
                double& g2) {
    const double t0 = w0 + w1, t1 = w0 * w0, t2 = t1 + w1 * t0;
    f1 = t0 + w2;
    f2 = t2 + w2 * f1;
    f3 = w0 * t1 + w1 * t2 + w2 * f2;
    g0 = f2 + w0 * (f1 + w0);
    g1 = f2 + w1 * (f1 + w1);
    g2 = f2 + w2 * (f1 + w2);
  };
  double in[10] = {};
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d &p0 = mesh.vertices[t[0]], &p1 = mesh.vertices[t[1]], &p2 = mesh.vertices[t[2]];
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);  // twice the area times the outward normal
    double f1x, f2x, f3x, g0x, g1x, g2x, f1y, f2y, f3y, g0y, g1y, g2y, f1z, f2z, f3z, g0z, g1z, g2z;
    sub(p0.x(), p1.x(), p2.x(), f1x, f2x, f3x, g0x, g1x, g2x);
    sub(p0.y(), p1.y(), p2.y(), f1y, f2y, f3y, g0y, g1y, g2y);
    sub(p0.z(), p1.z(), p2.z(), f1z, f2z, f3z, g0z, g1z, g2z);
    in[0] += n.x() * f1x;
    in[1] += n.x() * f2x;
    in[2] += n.y() * f2y;
    in[3] += n.z() * f2z;
    in[4] += n.x() * f3x;
    in[5] += n.y() * f3y;
    in[6] += n.z() * f3z;
    in[7] += n.x() * (p0.y() * g0x + p1.y() * g1x + p2.y() * g2x);
    in[8] += n.y() * (p0.z() * g0y + p1.z() * g1y + p2.z() * g2y);
    in[9] += n.z() * (p0.x() * g0z + p1.x() * g1z + p2.x() * g2z);
  }
  constexpr double mult[10] = {1.0 / 6, 1.0 / 24, 1.0 / 24, 1.0 / 24, 1.0 / 60, 1.0 / 60, 1.0 / 60,
                               1.0 / 120, 1.0 / 120, 1.0 / 120};
  for (int i = 0; i < 10; ++i) in[i] *= mult[i];
  const double volume = in[0];
  if (!(std::isfinite(volume) && volume != 0.0)) throw InvalidInput(key, "the mesh encloses no volume");
  // Unit density, then scaled; a surface oriented inwards has every integral negated.
  const double rho = mass ? *mass / volume : (volume > 0 ? *density : -*density);
  MassProperties p;
  p.mass = rho * volume;
  p.centre = Eigen::Vector3d(in[1], in[2], in[3]) / volume;
  const double xx = rho * in[4], yy = rho * in[5], zz = rho * in[6];
  const double xy = rho * in[7], yz = rho * in[8], zx = rho * in[9];
  p.inertia << yy + zz, -xy, -zx, -xy, xx + zz, -yz, -zx, -yz, xx + yy;
  if (!std::isfinite(p.mass) || !p.inertia.allFinite())
    throw InvalidInput(key, "its mass or moments of inertia overflow a double");
  return p;
}

namespace {

/// m, the height above O's level, along the upward vertical, of the lowest point of `part` at
/// tilt theta (the axis leaning by theta; every azimuth alike for a solid of revolution).
double lowest_point(const SolidPart& part, double c, double s) {
  const double top = part.z0 + part.height;
  auto ring = [c, s](double z, double radius) { return z * c - radius * s; };
  switch (part.shape) {
    case PartShape::Sphere: return (part.z0 + part.radius) * c - part.radius;
    case PartShape::Cone:
      return part.apex_up ? std::min(ring(part.z0, part.radius), ring(top, 0.0))
                          : std::min(ring(part.z0, 0.0), ring(top, part.radius));
    case PartShape::Cylinder:
    case PartShape::Tube: break;
  }
  return std::min(ring(part.z0, part.radius), ring(top, part.radius));
}

}  // namespace

std::optional<double> touch_tilt(const std::vector<SolidPart>& parts, double tip_radius, double rim_radius) {
  double size = tip_radius + rim_radius;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    validate(parts[i], fmt::format("body.part[{}]", i));
    size = std::max({size, std::abs(parts[i].z0), std::abs(parts[i].z0 + parts[i].height), parts[i].radius});
  }
  // m, the height of part k's lowest point over the table (< 0: below it).
  auto clearance = [&](std::size_t k, double theta) {
    return tip_radius + rim_radius * std::sin(theta) + lowest_point(parts[k], std::cos(theta), std::sin(theta));
  };
  const double below = -1e-9 * size;
  for (std::size_t i = 0; i < parts.size(); ++i)
    if (tip_radius + lowest_point(parts[i], 1.0, 0.0) < below)
      throw InvalidInput(fmt::format("body.part[{}]", i), "reaches below the tip with the body upright: it, not the "
                                                          "tip, would stand on the table (lower it less, or give "
                                                          "body.tip_radius)");
  constexpr int kScan = 4096;
  double lo = 0.0;
  for (int i = 1; i <= kScan; ++i) {
    const double theta = std::numbers::pi * i / kScan;
    std::size_t culprit = parts.size();
    for (std::size_t k = 0; k < parts.size(); ++k)
      if (clearance(k, theta) < below && (culprit == parts.size() || clearance(k, theta) < clearance(culprit, theta)))
        culprit = k;
    if (culprit == parts.size()) {
      lo = theta;
      continue;
    }
    // The root of the part that went below (the margin only told the tip's own part, at 0 to
    // rounding, from one that really reaches the table).
    double hi = theta;
    while (hi - lo > 1e-13) {
      const double mid = 0.5 * (lo + hi);
      (clearance(culprit, mid) < 0.0 ? hi : lo) = mid;
    }
    return hi;
  }
  return std::nullopt;
}

BodyAssembly assemble(const std::vector<MassProperties>& parts) {
  if (parts.empty()) throw InvalidInput("body.part", "give at least one part");
  BodyAssembly a;
  for (const auto& p : parts) a.total += p;
  const Eigen::Matrix3d& I = a.total.inertia;
  const double trace = I.trace();
  const double gyration = std::sqrt(trace / (2 * a.total.mass));  // a point mass at r has r
  auto small = [](double v, double scale) { return std::abs(v) < kGeneralBodyThreshold * scale ? 0.0 : v; };
  a.A = I(0, 0);
  a.B = I(1, 1);
  a.C = I(2, 2);
  a.Ixy = small(-I(0, 1), trace);
  a.Ixz = small(-I(0, 2), trace);
  a.Iyz = small(-I(1, 2), trace);
  a.offset_x = small(a.total.centre.x(), gyration);
  a.offset_y = small(a.total.centre.y(), gyration);
  a.length = a.total.centre.z();
  if (a.Ixz != 0.0 || a.Iyz != 0.0 || a.Ixy != 0.0) {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
    double best = 0.0;
    for (int k = 0; k < 3; ++k) best = std::max(best, std::abs(eig.eigenvectors()(2, k)));
    // acos loses half the digits near 1; asin of the transverse part keeps small tilts exact.
    a.principal_tilt = std::asin(std::sqrt(std::max(0.0, (1.0 - best) * (1.0 + best))));
  }
  // The part most to blame: the largest share of the transverse first moment or the products.
  double worst = -1.0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const MassProperties& p = parts[i];
    const double moment = std::hypot(p.centre.x(), p.centre.y()) * p.mass / (a.total.mass * gyration);
    const double products = (std::abs(p.inertia(0, 1)) + std::abs(p.inertia(0, 2)) + std::abs(p.inertia(1, 2))) / trace;
    if (std::max(moment, products) > worst) {
      worst = std::max(moment, products);
      a.main_part = i;
    }
  }
  return a;
}

Body body_of(const BodyAssembly& a, double gravity, const std::vector<std::string>& part_names) {
  if (a.general()) {
    const std::string part = a.main_part < part_names.size() ? part_names[a.main_part]
                                                             : fmt::format("body.part[{}]", a.main_part);
    std::string what;
    if (a.offset_x != 0.0 || a.offset_y != 0.0)
      what = fmt::format("its centre of mass is {:.3g} m off the z axis (x {:.3g}, y {:.3g})",
                         std::hypot(a.offset_x, a.offset_y), a.offset_x, a.offset_y);
    if (a.Ixy != 0.0 || a.Ixz != 0.0 || a.Iyz != 0.0)
      what += fmt::format("{}z is not a principal axis (products of inertia Ixy {:.3g}, Ixz {:.3g}, Iyz {:.3g} "
                          "kg m^2; principal axis {:.3g} rad from z)",
                          what.empty() ? "" : "; ", a.Ixy, a.Ixz, a.Iyz, a.principal_tilt);
    throw InvalidInput(part, what + ": the general body is integrated by `simulate --model nonlinear` only "
                                    "(`heavytop body` reports it)");
  }
  Body b;
  b.A = a.A;
  b.B = a.B;
  b.C = a.C;
  b.mass = a.total.mass;
  b.length = a.length;
  b.gravity = gravity;
  return b;
}

}  // namespace heavytop
