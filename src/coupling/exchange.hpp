// Particle-gas momentum exchange, coupling scheme 3 of [Zhu07 §3.2]: the force on each particle
// is computed first (drag closure + Model A pressure-gradient force), and the gas receives minus
// the same drag forces, distributed to the velocity faces with the SAME stencil weights as the
// interpolation [Hoomans96 eq. 40-41] (interpolation.hpp), per unit cell volume.
//
// Per particle i (V_i = pi d_i^3 / 6, also in 2-D: spheres confined to the x-z plane):
//   u_i   = gas velocity at x_i, eps_i = porosity at x_i, rho_i = gas density at x_i;
//   K_i   = closure K = beta/(1 - eps) at (eps_i, d_i, mu, rho_i, |u_i - v_i|) [Deen07 eq. 1];
//   c_i   = V_i K_i                                     (kg/s)
//   drag_i = c_i (u_i - v_i)                            (N, on the particle)
//   pres_i = -V_i grad p (x_i)                          (N, Model A [Zhu07 eq. 5])
// Gas source (semi-implicit form of GasSolver: S = K_us - K u + f per face, N m^-3):
//   K_face = sum_i w_if c_i / V_cell,  K_us,face = sum_i w_if c_i v_i / V_cell,  f = 0,
// so that with the gas velocity used for the particles sum_f S_f V_cell = -sum_i drag_i to
// round-off (Newton's third law). Stencil weights on faces the solver does not solve (walls,
// inflow, ghosts) are given to the solved faces of the stencil in proportion to their weights
// (the whole c_i reaches the gas); near walls this breaks the exact equality by O(h grad u).
// Periodic boundaries are not handled (particles within a cell of a periodic face).
#pragma once
#include "coupling/drag/drag_model.hpp"
#include "coupling/porosity.hpp"
#include "gas/gas_solver.hpp"
#include "particles/particle_store.hpp"
#include <vector>

namespace fluidem::coupling {

/// InputError for: scheme 1 or 2 (not implemented), gas Model B (not implemented: only the
/// Model A particle force is), a bad cube factor, a polydisperse closure without d_mean.
void validate(const CouplingSettings& c, const gas::GasSettings& gas);

/// Per-particle results of the gas -> particle step (all of size p.size()).
struct ParticleGasForces {
  std::vector<double> drag_x, drag_y, drag_z; ///< c_i (u_i - v_i), N
  std::vector<double> pres_x, pres_y, pres_z; ///< -V_i grad p (Model A), N
  std::vector<double> coeff;                  ///< c_i = V_i K_i, kg/s
  std::vector<double> ux, uy, uz;             ///< gas velocity at the particle, m/s
  std::vector<double> eps;                    ///< porosity at the particle
  void resize(std::size_t n);
};

/// Sets gs.porosity() (interior cells) from the particles (porosity.hpp).
void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c);

/// Gas -> particles: reads gs velocity, pressure, porosity, density and p.x/y/z, vx/vy/vz,
/// radius; writes `out`. The store is not modified (see add_forces()).
void compute_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                             const CouplingSettings& c, ParticleGasForces& out);

/// Particles -> gas: overwrites gs.drag_coefficient(d), drag_velocity_term(d) and zeroes
/// explicit_source(d) for all d, from out.coeff and the CURRENT particle velocities p.vx/vy/vz
/// (semi-implicit: use the velocities the drag acted with).
void deposit_momentum_source(gas::GasSolver& gs, const ParticleStore& p,
                             const ParticleGasForces& f);

/// After the gas step: drag_i = c_i (u_i - v_i) with the coefficients c_i that
/// deposit_momentum_source gave the gas, the NEW gas velocity u_i and the same particle
/// velocities v_i (so that the impulse the particles receive is minus the one the gas received,
/// [Zhu07 §3.2] scheme 3), and the Model A pressure force with the new pressure.
void update_particle_forces(const gas::GasSolver& gs, const ParticleStore& p, ParticleGasForces& f);

/// p.fx/fy/fz += drag + pressure force.
void add_forces(ParticleStore& p, const ParticleGasForces& f);

} // namespace fluidem::coupling
