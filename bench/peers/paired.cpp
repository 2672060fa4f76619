// heavytop's Taylor integrator against GSL rk8pd and Boost.Odeint on peers.cpp's asymmetric
// body, in paired rounds: each round runs every method once, each timed run after 1 ms of
// untimed ones (peers.cpp's warm_up), and the median of the per-round ratios (peer / heavytop)
// is printed beside the median times. Where the machine's speed drifts, the paired ratio is
// steadier than a ratio of medians. The tolerances are those peers.cpp's calibration at equal
// error chose (its table of 2026-12-06); recalibrate there if a method changes. Built by
// run.sh; by hand: build/peers/paired [ROUNDS].
#define HEAVYTOP_PEERS_LIBRARY
#include "peers.cpp"

int main(int argc, char** argv) {
  const int rounds = argc > 1 ? std::atoi(argv[1]) : 301;
  heavytop::Body asym;
  asym.A = 1.0, asym.B = 1.5, asym.C = 2.0, asym.mass = 1.0, asym.gravity = 9.81, asym.length = 0.1;
  heavytop::InitialState start;
  start.spin = 10.0, start.theta0 = 0.2;
  const Problem p{"asym", asym, start, 20.0};
  auto taylor = [](const Problem& q, double t) { return heavytop_run(q, t, heavytop::Integrator::Taylor); };
  struct Entry {
    const char* name;
    std::function<Output(const Problem&, double)> run;
    double tolerance[2];  // at the error levels 1e-6 and 1e-9
  };
  const std::vector<Entry> methods = {{"heavytop taylor", taylor, {1e-6, 5.6234e-9}},
                                      {"GSL rk8pd", gsl_rk8pd, {1e-2, 3.1623e-9}},
                                      {"odeint rkf78", odeint_rkf78, {1e-7, 1e-10}},
                                      {"odeint bulirsch_stoer", odeint_bulirsch_stoer, {1.7783e-6, 3.1623e-9}}};
  std::printf("%d paired rounds (CPU time of the thread)\n| level | method | tolerance | median CPU time | median paired ratio |\n"
              "| --- | --- | --- | --- | --- |\n", rounds);
  for (int level = 0; level < 2; ++level) {
    std::vector<std::vector<double>> times(methods.size()), ratios(methods.size());
    for (int r = 0; r < rounds; ++r) {
      std::vector<double> now(methods.size());
      for (std::size_t m = 0; m < methods.size(); ++m) {
        const double tol = methods[m].tolerance[level];
        warm_up([&] { methods[m].run(p, tol); });
        const double t0 = cpu_seconds();
        const Output out = methods[m].run(p, tol);
        now[m] = (cpu_seconds() - t0) * 1e6;
        if (out.failed) std::abort();
        times[m].push_back(now[m]);
      }
      for (std::size_t m = 0; m < methods.size(); ++m) ratios[m].push_back(now[m] / now[0]);
    }
    for (std::size_t m = 0; m < methods.size(); ++m)
      std::printf("| %s | %s | %.3g | %.1f us | %.2f |\n", level ? "1e-9" : "1e-6", methods[m].name,
                  methods[m].tolerance[level], median(times[m]), median(ratios[m]));
  }
}
