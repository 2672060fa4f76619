// Speed of the real-body computations: a closed mesh's mass properties (the defect check, which
// merges vertices and counts edges, and Eberly's integrals) and the steady-motion analyses.
//
// The mesh: a tessellated cylinder (a right prism on a regular polygon) with N sides, 4 N
// triangles. Counters: triangles_per_s.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

#include "heavytop/mass_properties.hpp"
#include "heavytop/precession.hpp"

namespace {

using namespace heavytop;

TriangleMesh prism(int n) {
  TriangleMesh m;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    m.vertices.emplace_back(0.02 * std::cos(t), 0.02 * std::sin(t), 0.0);
    m.vertices.emplace_back(0.02 * std::cos(t), 0.02 * std::sin(t), 0.01);
  }
  const auto pole = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(0, 0, 0);
  m.vertices.emplace_back(0, 0, 0.01);
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(n); ++k) {
    const std::uint32_t j = (k + 1) % n;
    m.triangles.push_back({2 * k, 2 * j, 2 * j + 1});
    m.triangles.push_back({2 * k, 2 * j + 1, 2 * k + 1});
    m.triangles.push_back({pole, 2 * j, 2 * k});
    m.triangles.push_back({pole + 1, 2 * k + 1, 2 * j + 1});
  }
  return m;
}

void BM_MeshMassProperties(benchmark::State& state) {
  const TriangleMesh mesh = prism(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(mass_properties(mesh, 700.0, std::nullopt, "k"));
  state.counters["triangles_per_s"] =
      benchmark::Counter(static_cast<double>(mesh.triangles.size()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_MeshMassProperties)->Arg(1536)->Arg(65536)->Unit(benchmark::kMillisecond);

void BM_SolidPart(benchmark::State& state) {
  const SolidPart cone{.shape = PartShape::Cone, .radius = 0.02, .height = 0.02, .density = 700.0, .mass = {}};
  for (auto _ : state) benchmark::DoNotOptimize(mass_properties(cone, "k"));
}
BENCHMARK(BM_SolidPart);

void BM_SteadyPrecession(benchmark::State& state) {
  const Body top = example_toy_top();
  for (auto _ : state) benchmark::DoNotOptimize(analyse_precession(top, 0.3, 200.0));
}
BENCHMARK(BM_SteadyPrecession);

void BM_PermanentRotations(benchmark::State& state) {
  const Body body{.A = 1.0, .B = 1.5, .C = 2.2, .mass = 1.0, .gravity = 1.0, .length = 0.3};
  for (auto _ : state) benchmark::DoNotOptimize(permanent_rotations(body, 0.8));
}
BENCHMARK(BM_PermanentRotations);

}  // namespace
