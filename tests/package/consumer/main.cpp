// An outside program using heavytop as a user would: through the installed package
// (find_package or pkg-config) or add_subdirectory. Exits non-zero if a result is wrong.
#include <heavytop/heavytop.hpp>
#ifdef HEAVYTOP_CONSUMER_SYMBOLIC
#include <heavytop/symbolic/derive.hpp>
#endif

#include <cmath>
#include <cstdio>
#include <string>

namespace {

int failures = 0;

void check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "FAIL: %s\n", what);
    ++failures;
  }
}

}  // namespace

int main() {
  const heavytop::Body top = heavytop::example_toy_top();
  heavytop::validate(top);

  // A symmetric body's linearized model is stable above C^2 w^2 = 4 A m g R.
  const heavytop::LinearModel model = heavytop::linear_model(heavytop::LinearModelKind::Linearized, top);
  const auto critical = heavytop::critical_spin(heavytop::stable_spin_intervals(model));
  const double expected = std::sqrt(4.0 * top.A * top.mgR()) / top.C;
  check(critical && std::abs(*critical - expected) <= 1e-12 * expected, "critical spin of the linearized model");

  // The closed-form motion starts where it was told to (to rounding: theta comes back from
  // cos(theta) through acos, 1 ulp off for the example).
  const heavytop::InitialState start = heavytop::example_motion();
  const heavytop::Simulation run =
      heavytop::simulate(heavytop::Model::LagrangeExact, top, start, heavytop::sample_times(1.0, 11));
  check(run.summary.ok() && run.trajectory.size() == 11, "simulate(LagrangeExact) ran");
  check(run.trajectory.size() > 0 && std::abs(run.trajectory.theta[0] - start.theta0) <= 1e-15 * start.theta0,
        "theta(0) == theta0");

  // version.hpp agrees with itself and with the package's version (CMake or pkg-config).
  const std::string version = std::to_string(HEAVYTOP_VERSION_MAJOR) + "." + std::to_string(HEAVYTOP_VERSION_MINOR) +
                              "." + std::to_string(HEAVYTOP_VERSION_PATCH);
  check(heavytop::kVersion == version && heavytop::kVersion == HEAVYTOP_VERSION_STRING, "version macros");
#ifdef HEAVYTOP_CONSUMER_EXPECTED_VERSION
  check(heavytop::kVersion == HEAVYTOP_CONSUMER_EXPECTED_VERSION, "version of the package");
#endif

#ifdef HEAVYTOP_CONSUMER_SYMBOLIC
  // Euler's equations on the moving axes, first order, give the paper's model (4).
  namespace sym = heavytop::symbolic;
  const sym::Derivation derivation = sym::derive(sym::Method::EulerMoving, sym::Sequence::PhiTheta, 1);
  check(sym::identify(derivation) == sym::PaperModel::Four, "symbolic: euler-moving gives model (4)");
#endif

  std::printf("heavytop %.*s: critical spin %.9g rad/s, %s\n", static_cast<int>(heavytop::kVersion.size()),
              heavytop::kVersion.data(), critical.value_or(-1.0), failures ? "FAILED" : "ok");
  return failures == 0 ? 0 : 1;
}
