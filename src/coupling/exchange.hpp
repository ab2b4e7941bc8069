// Particle-gas momentum exchange, coupling schemes 1-3 of [Zhu07 §3.2] (`c.scheme`), for gas
// Model A or Model B [Zhu07 eq. 4-7] (`gas.model`). Derivations and checks: docs/coupling.md
// ("Model A and Model B", "Forces and exchange").
//
// Per particle i (V_i = pi d_i^3 / 6; u_i, eps_i, rho_i interpolated at x_i [Hoomans96 eq. 40-41];
// K_i = beta/(1 - eps) of the closure [Deen07 eq. 1]):
//   c_i    = V_i K_i (Model A; form "total"),  V_i K_i / eps_i (Model B, form "buoyancy")  kg/s
//   drag_i = c_i (u_i - v_i)                                          N, on the particle
//   pres_i = -V_i grad p(x_i) (A [Zhu07 eq. 5]),  -V_i rho_i g (B, f_pf = f_d/eps - V rho g
//            [Zhu07 §3.1 after eq. 7, Feng & Yu 2004]; form "total": f_pf = the closure's total
//            force - V rho g [Hoomans96 eq. 34, with the buoyancy it neglects for a gas])
// Gas source, semi-implicit S = K_us - K u + f per face (N m^-3), with the interpolation's own
// stencil weights w_if:
//   Scheme 3 (default): K_face = sum_i w_if c_i / V_cell, K_us,face = sum_i w_if c_i v_i / V_cell,
//     f_face = 0 (A), -sum_i w_if pres_i / V_cell (B): sum_f S_f V_cell = -sum_i drag_i (A),
//     -sum_i (drag_i + pres_i) (B) to round-off (Newton's third law).
//   Schemes 1, 2: per cell c (particles whose centre is in c), C_c = V_s,c K_c (A; / eps_c in B)
//     at the cell averages (v_c mass-weighted, d_c Sauter mean), F_c = C_c (u_c - v_c)
//     [Chang08 eq. 2.10]; the gas gets -F_c, half to each face of c along each axis.
//     Scheme 2 [Chang08 eq. 2.11] shares F_c among the particles of c by surface area
//     (d_i^2 / sum d_j^2); scheme 1 gives each particle its own scheme-3 drag, so the third law
//     holds only on average (the exchange structure of the early codes, not their particle
//     force: docs/coupling.md).
// Weights on faces the solver does not solve (walls, ghosts; all v_y faces in 2-D) go to the
// solved faces of the stencil in proportion; an inflow face keeps its weight (it sets the face's
// pressure: gas_solver.hpp). Periodic ghost nodes pass their weights to their images.
#pragma once
#include "coupling/drag/drag_model.hpp"
#include "coupling/interpolation.hpp"
#include "coupling/porosity.hpp"
#include "coupling/trilinear.hpp"
#include "gas/gas_solver.hpp"
#include "particles/particle_store.hpp"
#include <array>
#include <vector>

namespace fluidem::coupling {

/// Faces that take the particles' momentum source (gas::GasSolver::face_role): the solved ones,
/// pressure faces, and inflow faces, where it sets the pressure on the face (gas_solver.hpp,
/// inflow_face_pressure).
inline bool takes_particle_source(unsigned char role) {
  return role == gas::GasSolver::solved || role == gas::GasSolver::pressure_face ||
         role == gas::GasSolver::inflow;
}

/// The particle-force form of a case: coupling.particle_force, or the gas model's default
/// (pressure_gradient in Model A, buoyancy in Model B).
ParticleForceForm particle_force_form(const CouplingSettings& c, const gas::GasSettings& gas);

/// InputError for: a bad cube factor, an unknown closure name, a polydisperse closure without
/// d_mean, a closure a case may not choose (its `refusal`), a particle-force form that does not
/// go with the gas model, and a closure not valid in the form (a total-force closure such as
/// wen_yu_single outside "total", to which the other forms would add the pressure force a second
/// time; a drag coefficient in "total"). Schemes 1, 2, 3 are all accepted. (The set-up names the
/// case-file key first: drag::drag_model_of_case.)
void validate(const CouplingSettings& c, const gas::GasSettings& gas);

/// Per-particle results of the gas -> particle step (all of size p.size()), and the cell
/// averages of schemes 1 and 2 (grid-sized, padded layout of gas::GasGrid; empty for scheme 3).
struct ParticleGasForces {
  std::vector<double> drag_x, drag_y, drag_z; ///< c_i (u_i - v_i) (scheme 2: s_i F_c), N
  /// Model A: the pressure force -V_i grad p; Model B: the buoyancy term -V_i rho_i g, N
  std::vector<double> pres_x, pres_y, pres_z;
  std::vector<double> coeff;      ///< c_i = V_i K_i (/ eps_i in Model B; scheme 2: s_i C_c), kg/s
  std::vector<double> ux, uy, uz; ///< gas velocity at the particle (scheme 2: u_c)
  std::vector<double> eps;        ///< porosity at the particle (scheme 2: eps_c)
  /// The scheme the forces were computed with (set by compute_particle_forces; read by
  /// deposit_momentum_source and update_particle_forces, whose signatures do not carry it).
  ExchangeScheme scheme = ExchangeScheme::scheme3;
  /// The porosity settings, which choose the mapping kernel (particle_mapping.hpp): set like
  /// `scheme`.
  PorositySettings porosity;
  std::vector<long> cell;         ///< schemes 1, 2: grid index of i's cell
  std::vector<double> cell_coeff; ///< schemes 1, 2: C_c = V_s,c K_c (/ eps_c in B), kg/s
  std::vector<double> cell_vx, cell_vy, cell_vz; ///< schemes 1, 2: v_c, m/s
  /// Schemes 1, 2: work space per cell (solid volume, mass, sums of d^2 and d^3), kept between
  /// flow steps so that the time loop does not allocate.
  std::vector<double> cell_solid, cell_mass, cell_d2, cell_d3;
  /// Trilinear-stencil kernel (porosity by cell): the 3 face stencils of particle i at
  /// 3 i + d (trilinear.hpp; 3 i + 1 unused in 2-D), built once per flow step by
  /// compute_particle_forces and reused by
  /// deposit_momentum_source and update_particle_forces, which therefore need the particles
  /// at the positions compute_particle_forces saw (as in a flow step: the particles do not move
  /// within it). Empty for the porous cube.
  std::vector<TrilinearStencil> face_stencils;
  /// With the stencils: the face pressure differences of the gas pressure the last loop over
  /// the particles read (face_pressure_differences), grid-sized per component.
  std::array<std::vector<double>, 3> face_dp;
  /// Per component: 1 on the faces that take the particles' source (takes_particle_source), 0
  /// elsewhere (grid-sized; deposit_momentum_source's work space).
  std::array<std::vector<double>, 3> takes_source;
  /// Distributed runs: the fixed-point sums (rank_sum.hpp), kept between flow steps.
  FixedPointSum fixed;
  void resize(std::size_t n); ///< every per-particle array n long, zeroed
  /// The per-particle arrays drag_x .. eps.
  std::array<std::vector<double>*, 11> per_particle();
};

/// Sets gs.porosity() (interior cells) from the particles (porosity.hpp).
void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c);
/// The same with caller-kept work space (no allocation once warmed up). With `ranks` (here and
/// below): `p` is this rank's particles, and every sum over particles into the grid is taken
/// over all ranks' in fixed point (rank_sum.hpp), the same bits on every rank.
void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c,
                     PorosityScratch& scratch, const RankSum* ranks = nullptr);

/// Gas -> particles: reads gs velocity, pressure, porosity, density and p.x/y/z, vx/vy/vz,
/// radius, mass; writes `out` (and out.scheme = c.scheme; the cell averages for schemes 1, 2).
/// The store is not modified (the integrator adds the forces in its kicks).
void compute_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                             const CouplingSettings& c, ParticleGasForces& out,
                             const RankSum* ranks = nullptr);

/// The particle loops of compute_particle_forces and update_particle_forces (and those of the
/// porosity) run on the OpenMP threads above core/parallel.hpp's kThreadedParticles, as the
/// DEM's do; per-particle results, independent of the thread count. Below it the loops' share of
/// the work does not pay for reading the gas fields, which the solver has just written on the
/// main thread, into the other core's cache: on the coupled Tsuji bed (2400 particles, 15 x 25
/// cells) two threads took 1.54 s for 0.1 s with the loops threaded from 256 particles, against
/// 1.46-1.48 s with them serial (one thread: 1.44-1.51 s); perf showed the gas interpolation 7x
/// slower on the worker thread than on the main one.

/// Particles -> gas: overwrites gs.drag_coefficient(d), drag_velocity_term(d) and
/// explicit_source(d) for all d (the latter 0 in Model A, minus the buoyancy terms f.pres_* in
/// Model B). Scheme 3: from f.coeff and the CURRENT particle velocities p.vx/vy/vz
/// (semi-implicit: use the velocities the drag acted with). Schemes 1, 2: from the cell
/// averages f.cell_coeff, f.cell_v* of compute_particle_forces (half to each face).
void deposit_momentum_source(gas::GasSolver& gs, const ParticleStore& p, ParticleGasForces& f,
                             const RankSum* ranks = nullptr);

/// After the gas step: drag_i = c_i (u_i - v_i) with the coefficients c_i that
/// deposit_momentum_source gave the gas, the NEW gas velocity u_i and the same particle
/// velocities v_i (so that the impulse the particles receive is minus the one the gas received,
/// [Zhu07 §3.2] scheme 3; scheme 1 the same per particle), and the Model A pressure force with
/// the new pressure (Model B: the buoyancy terms are kept, they are what the gas received).
/// Scheme 2: drag_i = s_i C_c (u_c,new - v_c) with the stored C_c, v_c.
void update_particle_forces(const gas::GasSolver& gs, const ParticleStore& p, ParticleGasForces& f);

} // namespace fluidem::coupling
