// The Basset history force [Zhu07 Table 3; Reeks & McKee 1984, Phys. Fluids 27:1573]:
//
//   F_B = C_B [ int_0^t (dw/dtau) / sqrt(t - tau) dtau + w(0)/sqrt(t) ],
//   C_B = 3/2 d^2 sqrt(pi rho_f mu)                       (basset_prefactor)
//
// w = u - v the slip (fluid minus particle velocity), t the time since the particle's history
// began; the w(0)/sqrt(t) term [Reeks & McKee 1984] is that of a particle that appears with
// slip w(0) (w jumps from 0 to w(0) at t = 0); it is optional per particle (start()).
// Validity: the unsteady Stokes equations (Re_p << 1, Basset 1888; Maxey & Riley 1983); at
// finite Re_p the kernel decays faster than t^-1/2 at long times (Mei & Adrian 1992), which
// this kernel does not model.
//
// Discretisation (a memory-efficient scheme after van Hinsberg, ten Thije Boonkkamp & Clercx
// 2011, J. Comput. Phys. 230:1465, with an exponential sum of our own fit):
// samples w_k = w(k DT) uniform in time (one per flow step; DT fixed for a run), w taken
// piecewise linear between samples. With s = t - tau the integral I(t_n) splits into
//   * the window s in [0, T_w], T_w = m DT (the last m intervals), integrated exactly for
//     piecewise-linear w:  sum_{j=0}^{m-1} g_j (w_{n-j} - w_{n-j-1}),
//     g_j = 2/sqrt(DT) (sqrt(j+1) - sqrt(j));
//   * the tail s > T_w, where the kernel s^-1/2 is replaced by
//     K(s) = sum_{i=1}^{14} a_i/sqrt(T_w) exp(-b_i s/T_w),
//     and each interval's contribution is integrated exactly for that kernel; the 14 sums
//     H_i(n) = sum over tail intervals of (dw/DT) int exp(-b_i (t_n - tau)/T_w) dtau obey
//     H_i(n+1) = exp(-b_i DT/T_w) H_i(n) + (w_{n+1-m} - w_{n-m}) phi_i,
//     phi_i = exp(-b_i) (1 - exp(-b_i/m)) m/b_i,
//     so the tail costs 14 numbers per axis, however long the history.
//   (a_i, b_i): a minimax fit of sigma^-1/2 on sigma = s/T_w in [1, 1e6] by Lawson-weighted
//   linear least squares on geometrically spaced b_i (tools/bbo_reference.py, fit_tail()):
//   |K(s) sqrt(s) - 1| <= 1.0e-3 for s/T_w in [1, 1e6] (max 0.99e-3, tested here:
//   tests/unit/coupling/basset_history_test.cpp); all a_i > 0, so for s/T_w > 1e6 K lies
//   between 0 and 1.001e-3/sqrt(T_w).
// Error bound (w twice differentiable, t = n DT, M1 = max|w'|, M2 = max|w''|):
//   |I_h(t) - I(t)| <= 9/8 M2 DT^{3/2}                    (piecewise-linear w: the newest
//                                                          interval M2 DT^{3/2}, the others
//                                                          M2 DT^{3/2}/8 by parts)
//                    + 1.0e-3 * 2 M1 sqrt(t)             (the tail kernel, t <= 1e6 T_w)
//   (for t > 1e6 T_w add 1.001e-3 (total variation of w over the older history)/sqrt(T_w)).
//   The window length m does not enter the bound; m trades the tail's share for memory:
//   3 (m + 1 + 14 + 1) doubles per particle (+ one count). Measured (basset_history_test,
//   t in [0.5, 20], m = 1..64): max |I_h - I| / max |I| = 0.8e-4 .. 1.1e-3 at DT = 0.01 and
//   0.9e-4 .. 3.2e-3 at DT = 0.05 for w = t, sin t, 1 - exp(-t/2), cos t with a slip start
//   (the tail's 1e-3 dominates at DT = 0.01). A sphere released from rest (Stokes drag, added
//   mass, Basset; Crank-Nicolson with the newest interval implicit): max |v - v_ref|/v_t =
//   3.3e-3, 7.4e-4, 2.4e-4, 6e-5 at DT = tau/8, tau/20, tau/40, tau/100 over 0..10 tau.
//   With backward Euler in the added-mass form below: 1.5e-3 at tau/100, 3.8e-4 at tau/400.
//
// Use in a time loop (the newest interval implicit). With samples w_0..w_n stored,
//   I(t_{n+1}) = c_new w_{n+1} + known(i),      c_new = 2/sqrt(DT)      (per axis)
// so  F_B(t_{n+1}) = C_B (c_new (u_{n+1} - v_{n+1}) + known): the part in v_{n+1} is
//   -C_B c_new v_{n+1} = -m_B v_{n+1}/DT,  m_B = C_B c_new DT = 2 C_B sqrt(DT) = 3 d^2
//   sqrt(pi rho_f mu DT)                                  (basset_added_mass)
// i.e. the newest interval acts as an added mass m_B on the step's velocity change:
//   (m + m_B) (v_{n+1} - v_n)/DT = ... + C_B (c_new (u_{n+1} - v_n) + known) - ...
// After the step, push(i, w_{n+1}).
// A particle with no samples (after resize()) has no history: c_new = 0 for it (has_history()
// false) and known = 0; its first push() (or start()) begins its history.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "core/vec3.hpp"

namespace fluidem::coupling::forces {

/// C_B = 3/2 d^2 sqrt(pi rho_f mu), kg s^-1/2 [Zhu07 Table 3].
double basset_prefactor(double d, double rho_f, double mu);

/// m_B = C_B c_new DT = 2 C_B sqrt(DT), kg: the newest interval of the history integral as an
/// added mass on (v_{n+1} - v_n)/DT (header comment).
double basset_added_mass(double prefactor, double dt);

/// The history integrals of many particles (one object for all), per-particle state in flat
/// vectors: no allocation per step.
class BassetHistory {
public:
  static constexpr int tail_terms = 14;
  /// The tail fit's coefficients (a_i, b_i) for sigma = s/T_w (header comment).
  static const std::array<double, tail_terms>& tail_a();
  static const std::array<double, tail_terms>& tail_b();
  /// Bound of |K(s) sqrt(s) - 1| for s/T_w in [1, 1e6].
  static constexpr double tail_relative_error = 1.0e-3;

  /// `dt` the sample spacing DT (> 0), `window` m >= 1 intervals integrated exactly.
  BassetHistory(double dt, int window, std::size_t n_particles = 0);

  double dt() const { return dt_; }
  int window() const { return m_; }
  std::size_t size() const { return count_.size(); }
  /// Number of samples particle i has (0: no history).
  std::uint64_t samples(std::size_t i) const { return count_[i]; }
  bool has_history(std::size_t i) const { return count_[i] > 0; }

  /// Grows or shrinks to n particles; new particles have no history.
  void resize(std::size_t n);
  /// Begins particle i's history with the sample w0 now. `slip_start`: the particle appears
  /// with slip w0 (the w(0)/sqrt(t) term); otherwise w is taken as w0 for all earlier times.
  void start(std::size_t i, const Vec3& w0, bool slip_start);
  /// Clears particle i's history.
  void clear(std::size_t i);

  /// 2/sqrt(DT), s^-1/2: the newest sample's weight in I(t_{n+1}) (0 without history).
  double c_new(std::size_t i) const { return count_[i] > 0 ? c_new_ : 0.0; }
  /// The part of I(t_{n+1}) known from the stored samples, m s^-1/2 (the slip's unit over
  /// sqrt(s)): I(t_{n+1}) = c_new(i) w_{n+1} + known(i).
  Vec3 known(std::size_t i) const;
  /// I(t_{n+1}) for a given w_{n+1} (= c_new(i) w_next + known(i)).
  Vec3 integral(std::size_t i, const Vec3& w_next) const;
  /// Appends the sample w_{n+1} (after the step). On a particle without history: start(i, w,
  /// false).
  void push(std::size_t i, const Vec3& w);

  /// Particle i's history as numbers (its sample count, samples, slip start and tail: the
  /// order of state()'s arrays), particle_width() of them; and back.
  std::size_t particle_width() const { return 1 + 3 * ring() + 3 + 3 * tail_terms; }
  void save_particle(std::size_t i, double* out) const;
  void load_particle(std::size_t i, const double* in);
  /// Reorders: new index k takes old particle new_to_old[k] (as ParticleStore::permute).
  void permute(const std::vector<std::uint32_t>& new_to_old);

  /// Everything a restart needs; set_state(state()) continues bitwise identically.
  struct State {
    double dt = 0.0;
    int window = 0;
    std::vector<std::uint64_t> count; ///< samples per particle
    std::vector<double> samples;      ///< ring of the last m+1 samples, [(3 i + axis)(m+1) + k]
    std::vector<double> start_slip;   ///< w(0) of a slip start (else 0), [3 i + axis]
    std::vector<double> tail;         ///< H_j(n+1), [(3 i + axis) 14 + j]
  };
  State state() const;
  /// Throws std::invalid_argument if dt/window differ from this object's or sizes mismatch.
  void set_state(const State& s);

  /// The tail kernel K(s) = sum a_i/sqrt(T_w) exp(-b_i s/T_w), s^-1/2 (for tests).
  double tail_kernel(double s) const;

private:
  std::size_t ring() const { return static_cast<std::size_t>(m_) + 1; }
  double sample(std::size_t i, int axis, std::uint64_t k) const {
    return samples_[(3 * i + static_cast<std::size_t>(axis)) * ring() + k % ring()];
  }

  double dt_;
  int m_;
  double c_new_;
  std::vector<double> g_;                  // window weights g_0..g_{m-1}
  std::array<double, tail_terms> c_{};     // a_i/sqrt(T_w)
  std::array<double, tail_terms> decay_{}; // exp(-b_i DT/T_w)
  std::array<double, tail_terms> phi_{};   // exp(-b_i)(1 - exp(-b_i/m)) m/b_i
  std::vector<std::uint64_t> count_;
  std::vector<double> samples_, start_slip_, tail_;
  std::vector<std::uint64_t> scratch_count_;
  std::vector<double> scratch_;
};

} // namespace fluidem::coupling::forces
