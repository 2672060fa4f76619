// SPEC section 17, uncertain inputs: JCGM 100's law of propagation for the linearized model's
// critical spin (exact derivatives), JCGM 101's adaptive Monte Carlo (7.9) for it and for the
// answer (SPEC 14), and JCGM 101 section 8's validation deciding which critical spin is reported.
#include "heavytop/uncertainty.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <complex>
#include <exception>
#include <limits>
#include <mutex>
#include <random>
#include <thread>
#include <tuple>

#include <boost/math/special_functions/beta.hpp>
#include <fmt/format.h>

#include "heavytop/linear_models.hpp"
#include "heavytop/stability.hpp"

namespace heavytop {
namespace {

// JCGM 101 7.9.2: M = max(J, 10^4) draws per batch, J = 100 / (1 - p) = 2000 for p = 0.95.
constexpr std::int64_t kBatch = 10000;
constexpr double kCoverage = 0.95;
constexpr double kCoverageFactor = 1.96;  // JCGM 100 G.1.3 for 95 % of a normal output
constexpr int kSignificantDigits = 2;     // SPEC 17: n_dig = 2
constexpr int kMaxRedraws = 1000;         // draws in a row outside the physical region before refusing
// The complex step: f(x + i h) = f(x) + i h f'(x) + O(h^2), so Im f / h is f' to rounding, with
// no subtraction to cancel (Squire and Trapp 1998); h relative to the parameter's size.
constexpr double kComplexStep = 1e-30;

/// SplitMix64's output function: a bijection of 64-bit integers with good avalanche.
std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

/// SplitMix64 as a generator (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number
/// generators"; Java's SplittableRandom): a Weyl sequence through the bijection above, which
/// passes BigCrush, one state word, so a generator per draw costs nothing to make.
class SplitMix64 {
 public:
  using result_type = std::uint64_t;
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return std::numeric_limits<result_type>::max(); }
  result_type operator()() {
    state_ += 0x9e3779b97f4a7c15ULL;
    return splitmix64(state_ - 0x9e3779b97f4a7c15ULL);
  }

 private:
  std::uint64_t state_;
};

bool is_body_key(const std::string& key) {
  return key == "A" || key == "B" || key == "C" || key == "mass" || key == "gravity" || key == "length";
}

double* field(Body& body, InitialState& state, const std::string& key) {
  if (key == "A") return &body.A;
  if (key == "B") return &body.B;
  if (key == "C") return &body.C;
  if (key == "mass") return &body.mass;
  if (key == "gravity") return &body.gravity;
  if (key == "length") return &body.length;
  if (key == "spin") return &state.spin;
  if (key == "theta0") return &state.theta0;
  if (key == "phi0") return &state.phi0;
  if (key == "theta_rate0") return &state.theta_rate0;
  if (key == "phi_rate0") return &state.phi_rate0;
  return nullptr;
}

double nominal(const Body& body, const InitialState& state, const std::string& key) {
  Body b = body;
  InitialState s = state;
  return *field(b, s, key);
}

/// The input's standard uncertainty u(x_i) in the key's unit (JCGM 100 4.3.7 for the
/// rectangular distribution: a / sqrt(3)).
double standard_uncertainty(const InputUncertainty& in, double x, UncertaintyDistribution d) {
  const double given = in.relative ? in.value * std::abs(x) : in.value;
  return d == UncertaintyDistribution::Uniform ? given / std::sqrt(3.0) : given;
}

/// A uniform-body's A moves B with it (SPEC 17) unless B is given its own uncertainty.
bool b_follows_a(const Body& body, const UncertaintyOptions& options) {
  return is_symmetric(body) && options.inputs.count("A") && !options.inputs.count("B");
}

/// True if the drawn body is inside SPEC 1's physical region (the realizability warning does not
/// count) with `length` on the nominal side of 0.
bool physical(const Body& drawn, const Body& nominal_body) {
  if (!(drawn.A > 0.0 && drawn.B > 0.0 && drawn.C > 0.0 && drawn.mass > 0.0 && drawn.gravity >= 0.0)) return false;
  if (nominal_body.length > 0.0 && !(drawn.length > 0.0)) return false;
  if (nominal_body.length < 0.0 && !(drawn.length < 0.0)) return false;
  try {
    validate(drawn);  // the triangle inequalities, with validate()'s own slack
  } catch (const InvalidInput&) {
    return false;
  }
  return true;
}

// ---- the critical spin's conditions, for exact derivatives ---------------------------------------

/// The linearized model's parameters (docs/linearization.md) in a scalar T (double or complex).
template <class T>
struct Params {
  T A, B, C, m, g, l;
  double d = 0.0;  // N m s, transverse damping (never uncertain)
};

/// The stability conditions whose sign changes bound the stable spins (stability.cpp's, the same
/// polynomials in s = w0^2): the critical spin's square is a root of one of them. Conservative:
/// the two stiffnesses, the quartic's middle coefficient and its discriminant; damped: the
/// Hurwitz coefficients and determinant.
template <class T>
std::vector<T> conditions(const Params<T>& p, T s) {
  const T k = p.m * p.g * p.l;
  const T k11 = -k + (p.C - p.B) * s, k22 = -k + (p.C - p.A) * s;
  const T gyro = p.C - p.A - p.B;  // G1_01 = -G1_10
  if (p.d == 0.0) {
    const T a2 = p.A * k22 + p.B * k11 + gyro * gyro * s;
    const T u = -p.A * k, v = -p.B * k, U = p.A * (p.C - p.A), V = p.B * (p.C - p.B);
    const T g2 = gyro * gyro, W = (p.C + (p.B - p.A)) * (p.C - (p.B - p.A));
    const T disc = (u - v) * (u - v) + T(2.0) * ((u - v) * (U - V) + (u + v) * g2) * s +
                   ((U - V) * (U - V) + g2 * W) * s * s;
    return {k11, k22, a2, disc};
  }
  const double d = p.d;
  const T a4 = p.A * p.B, a3 = d * (p.A + p.B);
  const T a2 = p.A * k22 + p.B * k11 + T(d * d) + gyro * gyro * s;
  const T a1 = d * (k11 + k22) - T(2.0 * d) * gyro * s;
  const T a0 = k11 * k22 + T(d * d) * s;
  const T h3 = a3 * a2 * a1 - a4 * a1 * a1 - a3 * a3 * a0;
  return {a2, a1, a0, h3};
}

Params<std::complex<double>> complex_params(const Body& b) {
  return {b.A, b.B, b.C, b.mass, b.gravity, b.length, b.damping.transverse};
}

}  // namespace

const std::vector<std::string>& uncertain_keys() {
  static const std::vector<std::string> keys = {"A",    "B",      "C",    "mass",        "gravity",  "length",
                                                "spin", "theta0", "phi0", "theta_rate0", "phi_rate0"};
  return keys;
}

std::string_view name(UncertaintyDistribution distribution) {
  return distribution == UncertaintyDistribution::Uniform ? "uniform" : "gaussian";
}

std::optional<UncertaintyDistribution> uncertainty_distribution_from_name(std::string_view n) {
  if (n == "gaussian") return UncertaintyDistribution::Gaussian;
  if (n == "uniform") return UncertaintyDistribution::Uniform;
  return std::nullopt;
}

std::string_view name(UncertaintyMethod method) {
  return method == UncertaintyMethod::Linear ? "linear" : "monte-carlo";
}

bool UncertaintyOptions::IsValid(std::string* why) const {
  auto fail = [why](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  const auto& keys = uncertain_keys();
  for (const auto& [key, in] : inputs) {
    if (std::find(keys.begin(), keys.end(), key) == keys.end())
      return fail(fmt::format("uncertainty.{}: unknown key (one of the body's or the motion's keys)", key));
    if (!std::isfinite(in.value) || in.value < 0.0)
      return fail(fmt::format("uncertainty.{}: must be a finite number >= 0 (a standard uncertainty), or a "
                              "percentage such as \"2%\"",
                              key));
  }
  if (draws < 0) return fail("uncertainty.draws: must be >= 0 (0: adaptive, JCGM 101 7.9)");
  if (max_draws < kBatch) return fail(fmt::format("uncertainty.max_draws: must be >= {}", kBatch));
  return true;
}

std::optional<double> largest_relative_uncertainty(const UncertaintyOptions& options, const Body& body,
                                                   const InitialState& initial) {
  std::optional<double> largest;
  for (const auto& [key, in] : options.inputs) {
    const double x = nominal(body, initial, key);
    if (x == 0.0) continue;
    const double relative = standard_uncertainty(in, x, options.distribution) / std::abs(x);
    if (!largest || relative > *largest) largest = relative;
  }
  return largest;
}

void validate(const UncertaintyOptions& options, const Body& body, const InitialState& initial) {
  std::string why;
  if (!options.IsValid(&why)) {
    const auto colon = why.find(": ");
    throw InvalidInput(why.substr(0, colon), why.substr(colon + 2));
  }
  for (const auto& [key, in] : options.inputs)
    if (in.relative && in.value > 0.0 && nominal(body, initial, key) == 0.0)
      throw InvalidInput("uncertainty." + key, "its nominal value is 0: give an absolute uncertainty, not a percentage");
}

std::pair<Body, InitialState> uncertain_draw(const Body& body, const InitialState& initial,
                                             const UncertaintyOptions& options, std::uint64_t index) {
  // One generator per draw, seeded from (seed, index): draw i is the same whatever thread takes
  // it and however many there are. SplitMix64 rather than std::mt19937_64: seeding the latter
  // (312 words, then its first twist) cost 3.5 us a draw, more than the critical spin itself.
  SplitMix64 rng(splitmix64(splitmix64(options.seed) + index));
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const bool follow = b_follows_a(body, options);
  for (int attempt = 0; attempt < kMaxRedraws; ++attempt) {
    Body b = body;
    InitialState s = initial;
    for (const std::string& key : uncertain_keys()) {  // a fixed order: the same numbers each time
      const auto it = options.inputs.find(key);
      if (it == options.inputs.end()) continue;
      double* x = field(b, s, key);
      const double spread = it->second.relative ? it->second.value * std::abs(*x) : it->second.value;
      *x += spread * (options.distribution == UncertaintyDistribution::Uniform ? uniform(rng) : normal(rng));
    }
    if (follow) b.B = b.A;
    if (physical(b, body)) return {b, s};
  }
  throw InvalidInput("uncertainty", fmt::format("{} draws in a row fell outside the physical region (SPEC 1's "
                                                "rules): the uncertainties are too large for this body",
                                                kMaxRedraws));
}

std::optional<double> linearized_critical_spin(const Body& body) {
  return critical_spin(stable_spin_intervals(linear_model(LinearModelKind::Linearized, body)));
}

std::optional<double> critical_spin_derivative(const Body& body, const std::string& key, bool with_b) {
  const std::optional<double> wc = linearized_critical_spin(body);
  if (!wc) return std::nullopt;
  if (!is_body_key(key) || *wc == 0.0) return 0.0;  // the motion does not enter; 0 stays 0 nearby
  const double s = *wc * *wc;
  using Complex = std::complex<double>;
  const Params<Complex> p0 = complex_params(body);
  // Which condition has its root at s_c: the one nearest to zero relative to its slope there.
  const std::vector<Complex> at = conditions(p0, Complex(s));
  const double hs = kComplexStep * s;
  const std::vector<Complex> slope = conditions(p0, Complex(s, hs));
  std::size_t which = 0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < at.size(); ++i) {
    const double dfds = slope[i].imag() / hs;
    if (dfds == 0.0) continue;
    const double distance = std::abs(at[i].real() / dfds) / s;  // relative distance of s_c to its root
    if (distance < best) best = distance, which = i;
  }
  // d f / d p at fixed s, by the complex step on the parameter (and on B with it).
  Params<Complex> p = p0;
  Complex* param = key == "A" ? &p.A : key == "B" ? &p.B : key == "C" ? &p.C : key == "mass" ? &p.m
                   : key == "gravity" ? &p.g : &p.l;
  const double size = std::abs(param->real());
  const double h = kComplexStep * (size > 0.0 ? size : 1.0);
  *param += Complex(0.0, h);
  if (key == "A" && with_b) p.B += Complex(0.0, h);
  const double dfdp = conditions(p, Complex(s))[which].imag() / h;
  const double dfds = slope[which].imag() / hs;
  const double dsdp = -dfdp / dfds;
  return dsdp / (2.0 * *wc);  // w_c = sqrt(s_c)
}

namespace {

/// What one draw gave.
struct DrawRecord {
  bool critical_done = false;
  std::optional<double> critical;  // rad/s
  bool answered = false;
  bool stays_up = false;           // "stays up" and proven
  std::optional<double> falls_at;  // s
  std::optional<double> max_tilt;  // rad
};

/// Draws [first, last) of `records` (grown as needed), on the options' threads; `answer`: SPEC
/// 14's answer too, else the critical spin only. Each draw lands in its own slot.
void evaluate(std::vector<DrawRecord>& records, std::int64_t first, std::int64_t last, bool answer,
              const Body& body, const InitialState& initial, const UncertaintyOptions& options,
              const AnswerOptions& answer_options) {
  if (static_cast<std::int64_t>(records.size()) < last) records.resize(last);
  std::atomic<std::int64_t> next{first};
  std::exception_ptr failure;
  std::once_flag failed;
  constexpr std::int64_t kBlock = 8;  // small: an unproven draw is a nonlinear run, thousands of times a proven one
  auto work = [&] {
    for (std::int64_t lo; (lo = next.fetch_add(kBlock)) < last;) {
      for (std::int64_t i = lo; i < std::min(last, lo + kBlock); ++i) {
        DrawRecord& r = records[i];
        if (r.answered || (r.critical_done && !answer)) continue;
        try {
          const auto [b, s] = uncertain_draw(body, initial, options, static_cast<std::uint64_t>(i));
          r.critical = linearized_critical_spin(b);
          if (answer) {
            // analyse_top()'s answer without its other two linear models, which the answer does
            // not use (a quarter of its cost for the toy top).
            const LyapunovStability lyapunov = analyse_lyapunov(b, s.spin);
            const Wander wander = axis_wander(b, s, answer_options.horizon, answer_options.integrator);
            const Answer a = answer_question(b, s, lyapunov, wander, answer_options);
            r.answered = true;
            r.stays_up = a.verdict == AnswerVerdict::StaysUp && a.proven;
            r.falls_at = a.falls_at;
            r.max_tilt = a.max_tilt;
          }
          r.critical_done = true;
        } catch (...) {
          std::call_once(failed, [&] { failure = std::current_exception(); });
          next = last;
        }
      }
    }
  };
  const unsigned cores = options.threads > 0 ? options.threads : std::max(1u, std::thread::hardware_concurrency());
  const std::int64_t blocks = (last - first + kBlock - 1) / kBlock;
  const unsigned threads = static_cast<unsigned>(std::clamp<std::int64_t>(blocks, 1, cores));
  std::vector<std::thread> pool;
  for (unsigned t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

/// JCGM 101 7.6 and 7.7: the estimate, standard uncertainty and probabilistically symmetric
/// coverage interval of the values (sorted here).
UncertainQuantity summarise(std::vector<double> values) {
  UncertainQuantity q;
  const std::size_t n = values.size();
  if (n == 0) return q;
  double sum = 0.0;
  for (double v : values) sum += v;
  q.value = sum / static_cast<double>(n);
  double ss = 0.0;
  for (double v : values) ss += (v - q.value) * (v - q.value);
  q.standard_uncertainty = n > 1 ? std::sqrt(ss / static_cast<double>(n - 1)) : 0.0;
  std::sort(values.begin(), values.end());
  // 7.7.2: q = pM (rounded), r = (M - q) / 2 (or (M - q + 1) / 2): [y_(r), y_(r + q)], 1-based.
  const std::size_t cover = static_cast<std::size_t>(std::llround(kCoverage * static_cast<double>(n)));
  const std::size_t r = std::max<std::size_t>(1, (n - cover + 1) / 2);
  q.lo = values[r - 1];
  q.hi = values[std::min(n, r + cover) - 1];
  return q;
}

/// JCGM 101 7.9.2 c): the numerical tolerance of a standard uncertainty u written with n_dig
/// significant digits as c x 10^l: delta = 10^l / 2.
double numerical_tolerance(double u) {
  if (!(u > 0.0) || !std::isfinite(u)) return 0.0;
  const double l = std::floor(std::log10(u)) - (kSignificantDigits - 1);
  return 0.5 * std::pow(10.0, l);
}

/// JCGM 101 7.9.4: twice the standard deviation of the h batch results' average, s^2 =
/// sum (x_r - mean)^2 / (h (h - 1)).
double twice_sd_of_mean(const std::vector<double>& x) {
  const std::size_t h = x.size();
  if (h < 2) return std::numeric_limits<double>::infinity();
  double mean = 0.0;
  for (double v : x) mean += v;
  mean /= static_cast<double>(h);
  double ss = 0.0;
  for (double v : x) ss += (v - mean) * (v - mean);
  return 2.0 * std::sqrt(ss / (static_cast<double>(h) * static_cast<double>(h - 1)));
}

/// 7.9.4's test for one quantity over its h batches: 2 s of the estimate, of the standard
/// uncertainty and (with_ends) of both ends of the interval are each <= delta, delta from the
/// standard uncertainty of all values pooled.
bool converged(const std::vector<UncertainQuantity>& batches, double pooled_u, bool with_ends) {
  const double delta = numerical_tolerance(pooled_u);
  std::vector<double> y, u, lo, hi;
  for (const UncertainQuantity& b : batches)
    y.push_back(b.value), u.push_back(b.standard_uncertainty), lo.push_back(b.lo), hi.push_back(b.hi);
  if (twice_sd_of_mean(y) > delta || twice_sd_of_mean(u) > delta) return false;
  return !with_ends || (twice_sd_of_mean(lo) <= delta && twice_sd_of_mean(hi) <= delta);
}

template <class Get>
std::vector<double> gather(const std::vector<DrawRecord>& records, std::int64_t first, std::int64_t last, Get get) {
  std::vector<double> out;
  for (std::int64_t i = first; i < last; ++i)
    if (const std::optional<double> v = get(records[i])) out.push_back(*v);
  return out;
}

std::optional<double> stays_up_value(const DrawRecord& r) { return r.stays_up ? 1.0 : 0.0; }
std::optional<double> tilt_value(const DrawRecord& r) { return r.max_tilt; }
std::optional<double> critical_value(const DrawRecord& r) { return r.critical; }

/// The batches' summaries of one quantity and the pooled values' standard uncertainty.
template <class Get>
bool batches_converged(const std::vector<DrawRecord>& records, std::int64_t batches, Get get, bool with_ends) {
  std::vector<UncertainQuantity> per_batch;
  for (std::int64_t r = 0; r < batches; ++r) {
    const std::vector<double> v = gather(records, r * kBatch, (r + 1) * kBatch, get);
    if (!v.empty()) per_batch.push_back(summarise(v));
  }
  if (per_batch.empty()) return true;  // no draw has the quantity: nothing to converge
  const double pooled = summarise(gather(records, 0, batches * kBatch, get)).standard_uncertainty;
  return converged(per_batch, pooled, with_ends);
}

/// 95 % Clopper-Pearson interval of a binomial proportion k / n (exact: its coverage is at
/// least 95 % for every p; Clopper and Pearson 1934).
std::pair<double, double> clopper_pearson(std::int64_t k, std::int64_t n) {
  const double alpha = 1.0 - kCoverage;
  const double lo = k == 0 ? 0.0 : boost::math::ibeta_inv(double(k), double(n - k + 1), alpha / 2.0);
  const double hi = k == n ? 1.0 : boost::math::ibeta_inv(double(k + 1), double(n - k), 1.0 - alpha / 2.0);
  return {lo, hi};
}

std::optional<UncertainOutcome> outcome(const std::vector<double>& values, std::int64_t n) {
  if (values.empty()) return std::nullopt;
  UncertainOutcome o;
  static_cast<UncertainQuantity&>(o) = summarise(values);
  o.fraction = static_cast<double>(values.size()) / static_cast<double>(n);
  return o;
}

}  // namespace

UncertaintyAnalysis analyse_uncertainty(const Body& body, const InitialState& initial,
                                        const UncertaintyOptions& options, const AnswerOptions& answer) {
  validate(body);
  validate(initial);
  validate(answer);
  validate(options, body, initial);
  refuse_general(body, "the uncertainty analysis");
  UncertaintyAnalysis out;
  out.coverage = kCoverage;
  std::vector<DrawRecord> records;

  // The answer's draws: a fixed count, or batches of 10^4 until 7.9's rule holds for
  // p_stays_up and the largest tilt's estimate and standard uncertainty. The ends of the largest
  // tilt's interval are left out of the rule: at two digits of a tilt that the inputs barely
  // move (the toy top's 0.0671 +- 0.0007 rad) they need ~7 10^5 draws, 40 s, for a number that
  // does not decide the answer (docs/uncertainty.md).
  std::int64_t n = options.draws;
  if (n > 0) {
    evaluate(records, 0, n, true, body, initial, options, answer);
  } else {
    std::int64_t h = 0;
    for (;;) {
      evaluate(records, h * kBatch, (h + 1) * kBatch, true, body, initial, options, answer);
      ++h;
      if (h < 2) continue;
      if (batches_converged(records, h, stays_up_value, false) && batches_converged(records, h, tilt_value, false))
        break;
      if ((h + 1) * kBatch > options.max_draws) {
        out.converged = false;
        break;
      }
    }
    n = h * kBatch;
  }
  out.draws = n;
  std::int64_t up = 0;
  std::vector<double> falls, tilts;
  for (std::int64_t i = 0; i < n; ++i) {
    const DrawRecord& r = records[i];
    up += r.stays_up ? 1 : 0;
    if (r.falls_at) falls.push_back(*r.falls_at);
    if (r.max_tilt) tilts.push_back(*r.max_tilt);
  }
  out.p_stays_up = static_cast<double>(up) / static_cast<double>(n);
  std::tie(out.p_stays_up_lo, out.p_stays_up_hi) = clopper_pearson(up, n);
  out.falls_at = outcome(falls, n);
  out.max_tilt = outcome(tilts, n);

  // JCGM 100: u_c^2 = sum (c_i u(x_i))^2 over the independent inputs, c_i exact.
  const std::optional<double> wc = linearized_critical_spin(body);
  const bool follow = b_follows_a(body, options);
  double variance = 0.0;
  for (const std::string& key : uncertain_keys()) {
    const auto it = options.inputs.find(key);
    if (it == options.inputs.end()) continue;
    const std::optional<double> c = critical_spin_derivative(body, key, follow && key == "A");
    out.sensitivity.emplace_back(key, c ? *c : std::numeric_limits<double>::quiet_NaN());
    if (c) {
      const double u = standard_uncertainty(it->second, nominal(body, initial, key), options.distribution);
      variance += (*c * u) * (*c * u);
    }
  }
  if (!wc) {
    out.method = UncertaintyMethod::MonteCarlo;
    return out;  // no critical spin to propagate (SPEC 5: null)
  }
  const double uc = std::sqrt(variance);
  out.critical_linear = UncertainQuantity{*wc, uc, *wc - kCoverageFactor * uc, *wc + kCoverageFactor * uc};

  // JCGM 101 7.9 for the critical spin, whatever `draws` says (SPEC 17), reusing the answer's
  // draws (the same inputs for the same index).
  std::int64_t h = 0;
  for (;;) {
    evaluate(records, h * kBatch, (h + 1) * kBatch, false, body, initial, options, answer);
    ++h;
    if (h >= 2 && batches_converged(records, h, critical_value, true)) break;
    if ((h + 1) * kBatch > options.max_draws) {
      out.converged = false;
      break;
    }
  }
  out.critical_draws = h * kBatch;
  const std::vector<double> critical = gather(records, 0, out.critical_draws, critical_value);
  const bool every_draw = static_cast<std::int64_t>(critical.size()) == out.critical_draws;
  if (!critical.empty()) out.critical_monte_carlo = summarise(critical);

  // JCGM 101 8.2: the linear interval is validated when both its ends agree with the Monte
  // Carlo's to delta, the numerical tolerance of u_c at two significant digits.
  out.tolerance = numerical_tolerance(uc);
  if (out.critical_monte_carlo) {
    out.d_low = std::abs(out.critical_linear->lo - out.critical_monte_carlo->lo);
    out.d_high = std::abs(out.critical_linear->hi - out.critical_monte_carlo->hi);
  }
  const bool valid = every_draw && out.critical_monte_carlo && out.d_low <= out.tolerance &&
                     out.d_high <= out.tolerance;
  out.method = valid ? UncertaintyMethod::Linear : UncertaintyMethod::MonteCarlo;
  out.critical_spin = valid ? out.critical_linear : out.critical_monte_carlo;
  return out;
}

}  // namespace heavytop
