// The Basset history integrals: window + exponential tail (basset_history.hpp).
#include "coupling/forces/basset_history.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace fluidem::coupling::forces {

namespace {
// sigma^-1/2 ~ sum a_i exp(-b_i sigma), sigma in [1, 1e6], max relative error 0.99e-3:
// tools/bbo_reference.py (fit_tail), printed with 17 significant digits.
constexpr std::array<double, BassetHistory::tail_terms> kTailA = {
    0.0010352127426242518, 0.0002907450611967198, 0.0012537806228671714, 0.0021331776831572525,
    0.003994811225467936,  0.00729404582133838,   0.013532454688554827,  0.024751580490110742,
    0.045904362894901816,  0.08396422757419571,   0.15574064216001604,   0.2847765623140645,
    0.528661429591275,     0.9665109092721991};
constexpr std::array<double, BassetHistory::tail_terms> kTailB = {
    2.5118864315095823e-07, 8.521190030032091e-07,  2.890683217882633e-06, 9.806200116061499e-06,
    3.326603209973349e-05,  0.00011284991929217926, 0.0003828260685275239, 0.0012986788086643945,
    0.004405568969117136,   0.014945218026317637,   0.050699363333070305,  0.17198982563200566,
    0.5834491436627729,     1.9792618661593413};
constexpr std::size_t kT = BassetHistory::tail_terms;
} // namespace

double basset_prefactor(double d, double rho_f, double mu) {
  return 1.5 * d * d * std::sqrt(std::numbers::pi * rho_f * mu);
}

double basset_added_mass(double prefactor, double dt) {
  return 2.0 * prefactor * std::sqrt(dt);
}

const std::array<double, BassetHistory::tail_terms>& BassetHistory::tail_a() {
  return kTailA;
}
const std::array<double, BassetHistory::tail_terms>& BassetHistory::tail_b() {
  return kTailB;
}

BassetHistory::BassetHistory(double dt, int window, std::size_t n_particles)
    : dt_(dt), m_(window), c_new_(0.0) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument("BassetHistory: DT must be positive, got " + std::to_string(dt));
  if (window < 1)
    throw std::invalid_argument("BassetHistory: window must be >= 1, got " +
                                std::to_string(window));
  c_new_ = 2.0 / std::sqrt(dt);
  g_.resize(static_cast<std::size_t>(m_));
  for (std::size_t j = 0; j < g_.size(); ++j) {
    const double x = static_cast<double>(j);
    g_[j] = 2.0 / std::sqrt(dt) * (std::sqrt(x + 1.0) - std::sqrt(x));
  }
  const double m = static_cast<double>(m_);
  const double t_w = m * dt;
  for (std::size_t i = 0; i < kT; ++i) {
    c_[i] = kTailA[i] / std::sqrt(t_w);
    decay_[i] = std::exp(-kTailB[i] / m);
    phi_[i] = std::exp(-kTailB[i]) * (-std::expm1(-kTailB[i] / m)) * m / kTailB[i];
  }
  resize(n_particles);
}

void BassetHistory::resize(std::size_t n) {
  count_.resize(n, 0);
  samples_.resize(3 * n * ring(), 0.0);
  start_slip_.resize(3 * n, 0.0);
  tail_.resize(3 * n * kT, 0.0);
}

void BassetHistory::save_particle(std::size_t i, double* out) const {
  const std::size_t ns = 3 * ring(), nt = 3 * kT;
  out[0] = static_cast<double>(count_[i]); // a whole number below 2^53: exact
  std::copy_n(samples_.data() + ns * i, ns, out + 1);
  std::copy_n(start_slip_.data() + 3 * i, 3, out + 1 + ns);
  std::copy_n(tail_.data() + nt * i, nt, out + 1 + ns + 3);
}

void BassetHistory::load_particle(std::size_t i, const double* in) {
  const std::size_t ns = 3 * ring(), nt = 3 * kT;
  count_[i] = static_cast<std::uint64_t>(in[0]);
  std::copy_n(in + 1, ns, samples_.data() + ns * i);
  std::copy_n(in + 1 + ns, 3, start_slip_.data() + 3 * i);
  std::copy_n(in + 1 + ns + 3, nt, tail_.data() + nt * i);
}

void BassetHistory::clear(std::size_t i) {
  count_[i] = 0;
  std::fill_n(samples_.begin() + static_cast<std::ptrdiff_t>(3 * i * ring()), 3 * ring(), 0.0);
  std::fill_n(start_slip_.begin() + static_cast<std::ptrdiff_t>(3 * i), 3, 0.0);
  std::fill_n(tail_.begin() + static_cast<std::ptrdiff_t>(3 * i * kT), 3 * kT, 0.0);
}

void BassetHistory::start(std::size_t i, const Vec3& w0, bool slip_start) {
  clear(i);
  count_[i] = 1;
  for (int a = 0; a < 3; ++a) {
    const std::size_t r = 3 * i + static_cast<std::size_t>(a);
    samples_[r * ring()] = w0[a]; // sample 0, slot 0
    start_slip_[r] = slip_start ? w0[a] : 0.0;
  }
}

Vec3 BassetHistory::known(std::size_t i) const {
  const std::uint64_t c = count_[i];
  if (c == 0) return {};
  const std::uint64_t n = c - 1; // newest sample index
  const std::uint64_t m = static_cast<std::uint64_t>(m_);
  const std::uint64_t k0 = n + 2 > m ? std::max<std::uint64_t>(1, n + 2 - m) : 1;
  const double inv_sqrt_t = 1.0 / std::sqrt(static_cast<double>(n + 1) * dt_);
  Vec3 out;
  for (int a = 0; a < 3; ++a) {
    const std::size_t r = 3 * i + static_cast<std::size_t>(a);
    double s = -g_[0] * sample(i, a, n);
    for (std::uint64_t k = k0; k <= n; ++k)
      s += g_[n + 1 - k] * (sample(i, a, k) - sample(i, a, k - 1));
    const double* h = &tail_[r * kT];
    double tail = 0.0;
    for (std::size_t j = 0; j < kT; ++j) tail += c_[j] * h[j];
    out[a] = s + tail + start_slip_[r] * inv_sqrt_t;
  }
  return out;
}

Vec3 BassetHistory::integral(std::size_t i, const Vec3& w_next) const {
  return known(i) + c_new(i) * w_next;
}

void BassetHistory::push(std::size_t i, const Vec3& w) {
  if (count_[i] == 0) {
    start(i, w, false);
    return;
  }
  const std::uint64_t k_new = count_[i]; // index of the new sample
  const std::uint64_t m = static_cast<std::uint64_t>(m_);
  for (int a = 0; a < 3; ++a) {
    const std::size_t r = 3 * i + static_cast<std::size_t>(a);
    samples_[r * ring() + k_new % ring()] = w[a];
  }
  count_[i] = k_new + 1;
  // H(n+2) = decay H(n+1) + (w_k - w_{k-1}) phi, k = count - m, the interval that leaves the
  // window.
  const std::uint64_t c = k_new + 1;
  const bool leaves = c > m && c - m >= 1;
  for (int a = 0; a < 3; ++a) {
    const std::size_t r = 3 * i + static_cast<std::size_t>(a);
    const double dw = leaves ? sample(i, a, c - m) - sample(i, a, c - m - 1) : 0.0;
    double* h = &tail_[r * kT];
    for (std::size_t j = 0; j < kT; ++j) h[j] = decay_[j] * h[j] + dw * phi_[j];
  }
}

void BassetHistory::permute(const std::vector<std::uint32_t>& new_to_old) {
  const std::size_t n = new_to_old.size();
  if (n != size())
    throw std::invalid_argument("BassetHistory::permute: " + std::to_string(n) + " indices for " +
                                std::to_string(size()) + " particles");
  scratch_count_.resize(n);
  for (std::size_t k = 0; k < n; ++k) scratch_count_[k] = count_[new_to_old[k]];
  count_.swap(scratch_count_);
  auto move_rows = [&](std::vector<double>& v, std::size_t width) {
    scratch_.resize(v.size());
    for (std::size_t k = 0; k < n; ++k)
      std::copy_n(v.begin() + static_cast<std::ptrdiff_t>(new_to_old[k] * width), width,
                  scratch_.begin() + static_cast<std::ptrdiff_t>(k * width));
    v.swap(scratch_);
  };
  move_rows(samples_, 3 * ring());
  move_rows(start_slip_, 3);
  move_rows(tail_, 3 * kT);
}

BassetHistory::State BassetHistory::state() const {
  return {dt_, m_, count_, samples_, start_slip_, tail_};
}

void BassetHistory::set_state(const State& s) {
  if (s.dt != dt_ || s.window != m_)
    throw std::invalid_argument("BassetHistory::set_state: DT/window " + std::to_string(s.dt) +
                                "/" + std::to_string(s.window) + " differ from this run's " +
                                std::to_string(dt_) + "/" + std::to_string(m_));
  const std::size_t n = s.count.size();
  if (s.samples.size() != 3 * n * ring() || s.start_slip.size() != 3 * n ||
      s.tail.size() != 3 * n * kT)
    throw std::invalid_argument("BassetHistory::set_state: array sizes do not match " +
                                std::to_string(n) + " particles");
  count_ = s.count;
  samples_ = s.samples;
  start_slip_ = s.start_slip;
  tail_ = s.tail;
}

double BassetHistory::tail_kernel(double s) const {
  const double t_w = static_cast<double>(m_) * dt_;
  double k = 0.0;
  for (std::size_t j = 0; j < kT; ++j) k += kTailA[j] * std::exp(-kTailB[j] * s / t_w);
  return k / std::sqrt(t_w);
}

} // namespace fluidem::coupling::forces
