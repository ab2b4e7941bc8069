// The particle-fluid forces beyond drag and pressure [Zhu07 Table 3] in the flow step
// (`[coupling.forces]`; kernels in src/coupling/forces/, derivation and checks in
// docs/coupling.md, "Fluid forces beyond drag"). Per particle i, at the flow step from t^n to
// t^{n+1} = t^n + DT, with u the gas velocity at x^n_i (u^n before the gas step, u^{n+1} after),
// v^n_i its velocity, w = u^{n+1} - v^n, G = grad u^{n+1} at x^n_i (central differences of the
// interpolated velocity over half a cell), Omega = curl u, Du/Dt = (u^{n+1} - u^n)/DT + G u^{n+1}:
//   virtual mass  F_vm = m_a (Du/Dt - dv/dt),  m_a = C rho_f V
//   Basset        F_B  = K_B [c_new w^{n+1} + H_i],  K_B = 3/2 d^2 sqrt(pi rho_f mu), the history
//                 H_i of the samples w^k = u^k(x^k) - v^k, k <= n, and the weight c_new of the
//                 newest (BassetHistory)
//   Saffman-Mei   F_S  (saffman_mei.hpp),   Magnus F_M (magnus.hpp)
//   fluid torque  T = k (Omega/2 - omega) (fluid_torque.hpp: k = pi mu d^3 in the Stokes limit),
//                 held over the step as the exact mean torque of the step without other
//                 torques, T_held = k (Omega/2 - omega^n) (1 - exp(-k DT/I)) / (k DT/I): the
//                 spin relaxes without overshoot for any DT (an exponential integrator). Its
//                 reaction, a couple on the gas, has no place in the gas equations: not given.
// The unknown dv/dt is implicit: m_x = m_a + m_B (m_B = K_B c_new DT, the newest Basset
// interval) is added to the particle's inertia at set-up (p.inv_mass = 1/(m + m_x)), and the
// held force over the step is
//   F_held = F_S + F_M + m_a Du/Dt + K_B [c_new (u^{n+1} - v^n) + H_i] - m_x (g + a(x^n)),
// so that (m + m_x) dv/dt = F_other + m (g + a) + F_held + m_x (g + a): the equation of motion
// with the added mass and the Basset force of the step, stable for any density ratio (no
// explicit dv/dt); a(x) a body-force field (acceleration of the particle's own mass), taken at
// the step's start. The impulse the fluid gave the particle over the step, J = DT (F_held +
// m_x (g + a)) -
// m_x (v^{n+1} - v^n), is known at the next flow step: the gas receives -J/DT then (two-way),
// with the particle's interpolation weights, so that Newton's third law holds over the run
// with a lag of one flow step.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/body_force.hpp"
#include "core/coupling_settings.hpp"
#include "coupling/exchange.hpp"
#include "coupling/forces/basset_history.hpp"
#include "coupling/rank_sum.hpp"
#include "gas/gas_solver.hpp"
#include "particles/particle_store.hpp"

namespace fluidem {

class FluidForces {
public:
  /// flow_dt: the flow step DT (the Basset samples' spacing); n: the particles.
  /// field: the case's body-force field, or nullptr (its acceleration acts on the particle's own
  /// mass: the held force takes -m_x a(x^n) with the added inertia, as it takes -m_x g).
  FluidForces(const coupling::FluidForceSettings& s, const gas::GasSolver& gs, double flow_dt,
              std::size_t n, const BodyForceSpec* field);

  /// The inertia m_x added to a moving particle of diameter d, kg (virtual mass and the newest
  /// Basset interval, with the fluid density at set-up).
  double added_inertia(double d) const;

  /// At the start of a flow step, after compute_particle_forces (f.u = u^n(x^n)): the fluid's
  /// impulse on each particle over the last step (for the gas's reaction), the Basset sample
  /// w^n, and u^n kept for Du/Dt.
  void begin_step(const ParticleStore& p, const coupling::ParticleGasForces& f);
  /// Two-way: minus the last step's impulses / DT into the gas's explicit source (after
  /// deposit_momentum_source, which overwrites it). ranks: the particles are this rank's, and
  /// the sums over all ranks' particles are taken in fixed point (coupling/rank_sum.hpp).
  void deposit_reaction(gas::GasSolver& gs, const ParticleStore& p,
                        const coupling::RankSum* ranks = nullptr);
  /// After the gas step (f.u = u^{n+1}(x^n)): the held forces F_held of the step.
  void compute(const gas::GasSolver& gs, const ParticleStore& p,
               const coupling::ParticleGasForces& f);

  /// F_held, N, per particle and axis.
  const std::array<std::vector<double>, 3>& force() const { return held_; }
  /// The held fluid torque about axis d, N m; nullptr without a torque model.
  const double* torque(int d) const {
    return s_.torque == "off" ? nullptr : torque_[static_cast<std::size_t>(d)].data();
  }

  /// Every per-particle number of the state (checkpoints), by name.
  std::vector<std::pair<std::string, std::vector<double>>> state() const;
  void restore(const std::vector<std::pair<std::string, std::vector<double>>>& s);
  void permute(const std::vector<std::uint32_t>& new_to_old);

  /// The per-particle numbers of state(), particle by particle (runs on MPI ranks carry them
  /// with their particles): numbers per particle (for these settings, before any particle),
  /// the particles' numbers into `out` (width() each, sized for all of them), and back for n
  /// particles.
  static std::size_t width(const coupling::FluidForceSettings& s);
  void save(std::span<double> out) const;
  void load(std::span<const double> in, std::size_t n);
  /// The state() of n particles whose numbers `in` holds (width() each).
  std::vector<std::pair<std::string, std::vector<double>>> unpacked(const std::vector<double>& in,
                                                                    std::size_t n) const;

private:
  coupling::FluidForceSettings s_;
  double dt_, rho_, mu_;
  std::array<double, 3> g_;
  const BodyForceSpec* field_;
  std::array<std::vector<double>, 3> held_;     ///< F_held, N
  std::array<std::vector<double>, 3> physical_; ///< F_held + m_x g, N (the impulse's rate)
  std::array<std::vector<double>, 3> v_start_;  ///< v^n, m/s
  std::array<std::vector<double>, 3> u_start_;  ///< u^n(x^n), m/s
  std::array<std::vector<double>, 3> reaction_; ///< J / DT of the last step, N
  std::array<std::vector<double>, 3> torque_;   ///< held fluid torque, N m
  bool started_ = false;                        ///< a step has been computed
  std::unique_ptr<coupling::forces::BassetHistory> basset_;
  coupling::FixedPointSum fixed_; ///< deposit_reaction() on ranks
};

} // namespace fluidem
