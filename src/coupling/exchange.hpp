// Particle-gas momentum exchange, coupling schemes 1-3 of [Zhu07 §3.2] (`c.scheme`), for gas
// Model A or Model B [Zhu07 eq. 4-7] (`gas.model`).
//
// Scheme 3 (default): the force on each particle is computed first (drag closure + the Model A
// pressure-gradient force or the Model B buoyancy term), and the gas receives minus the same
// forces, distributed to the velocity faces with the SAME stencil weights as the interpolation
// [Hoomans96 eq. 40-41] (interpolation.hpp), per unit cell volume.
//
// Model A and Model B. The gas solver (gas_equations.cpp) solves, per unit volume,
//   Model A [Zhu07 eq. 5]: d(eps rho u)/dt + conv = -eps grad p - F_A + visc + eps rho g,
//   Model B [Zhu07 eq. 7]: d(eps rho u)/dt + conv = -grad p   - F_B + visc + eps rho g,
// (gravity eps rho g from gas.gravity in both), F = the particle force on the gas per unit
// volume with the sign of the force ON THE PARTICLES. In Model A the particle i gets
// f_d,i - V_i grad p (drag f_d,i = V_i K_i (u_i - v_i) plus the pressure force) and
// F_A = sum_i f_d,i / V_cell (drag only: the pressure part is the -eps grad p of the gas).
// Model B: the particles get the WHOLE particle-fluid force f_pf,i, no separate pressure force,
// and F_B = sum_i f_pf,i / V_cell. Derivation (Feng & Yu 2004, quoted in [Zhu07 §3.1] after
// eq. 7: F_B = F_A/eps_f - rho_f eps_s g): drop the inertial and viscous terms of the Model A
// equation, eps grad p = -F_A + eps rho g, so grad p = -F_A/eps + rho g; the total force on the
// particles per unit volume is then F_A - eps_s grad p = F_A (1 + eps_s/eps) - eps_s rho g
// = F_A/eps - eps_s rho g (eps + eps_s = 1). Model B calls this F_B; with eps_s V_cell =
// sum_i V_i it is sum_i f_pf,i / V_cell with, per particle,
//   f_pf,i = f_d,i / eps_i - V_i rho_i g
// (drag scaled by 1/eps, plus a buoyancy-like term that uses the gas weight rho g instead of the
// pressure gradient). Check, steady uniform fixed bed, Model B gas: 0 = -grad p - F_B + eps rho g
// = -grad p - F_A/eps + eps_s rho g + eps rho g  ->  grad p = -F_A/eps + rho g: the same pressure
// gradient as Model A. The total force on the particles per unit volume is the same as well
// (F_B = F_A - eps_s grad p), = -grad p + eps rho g: the pressure drop per length less the
// weight of the gas in the bed per volume (g points down; 0 gravity: the pressure drop alone).
//
// Per particle i (V_i = pi d_i^3 / 6, also in 2-D: spheres confined to the x-z plane):
//   u_i   = gas velocity at x_i, eps_i = porosity at x_i, rho_i = gas density at x_i;
//   K_i   = closure K = beta/(1 - eps) at (eps_i, d_i, mu, rho_i, |u_i - v_i|) [Deen07 eq. 1];
//   c_i   = V_i K_i (Model A), V_i K_i / eps_i (Model B)   (kg/s)
//   drag_i = c_i (u_i - v_i)                            (N, on the particle)
//   pres_i = -V_i grad p (x_i)   (N, Model A [Zhu07 eq. 5])
//   pres_i = -V_i rho_i g        (N, Model B: the buoyancy term of f_pf,i; g = gas.gravity)
// Gas source (semi-implicit form of GasSolver: S = K_us - K u + f per face, N m^-3):
//   K_face = sum_i w_if c_i / V_cell,  K_us,face = sum_i w_if c_i v_i / V_cell,
//   f_face = 0 (Model A),  f_face = -sum_i w_if pres_i / V_cell (Model B),
// so that with the gas velocity used for the particles sum_f S_f V_cell = -sum_i drag_i (A),
// -sum_i (drag_i + pres_i) (B) to round-off (Newton's third law). Stencil weights on faces the
// solver does not solve (walls, inflow, ghosts) are given to the solved faces of the stencil in
// proportion to their weights (the whole c_i and pres_i reach the gas); near walls this breaks
// the exact equality of the drag by O(h grad u). Periodic axes: stencil nodes in the ghost
// layer (or the copy face 0 along d) are the images of unknowns at the other end
// (interpolation.hpp, periodic_image): their weights go there, so the equalities above hold
// across periodic faces too.
//
// Cell averages (schemes 1 and 2), per interior cell c over the particles whose CENTRE is in c
// (GasGrid::cell_of, points outside clamped onto the domain):
//   V_s,c = sum_i V_i,  v_c = sum_i m_i v_i / sum_i m_i (mass-weighted),
//   d_c = sum_i d_i^3 / sum_i d_i^2 (Sauter mean: the diameter with the cell's solids volume
//         per surface area; = d for identical particles),
//   eps_c, rho_c = the cell's porosity and gas density, u_c = mean of the two faces of c per
//   component (as in the fields output);
//   K_c = closure K at (eps_c, d_c, mu, rho_c, |u_c - v_c|),
//   C_c = V_s,c K_c (Model A), V_s,c K_c / eps_c (Model B) (kg/s),
//   F_c = C_c (u_c - v_c) = beta_c V_cell (u_c - v_c) (Model A) when V_s,c = (1 - eps_c) V_cell
//         [Chang08 eq. 2.10].
// Gas source of schemes 1 and 2: -F_c in semi-implicit form, split HALF to each of the two
// faces of c along each axis d (our choice; [Zhu07 §3.2] and [Chang08 eq. 2.10] only say "per
// cell"; the half/half split is the one for which the face sum is exactly -C_c (u_c - v_c)
// with u_c the mean of the two faces):
//   K_face += C_c / (2 V_cell),  K_us,face += C_c v_c,d / (2 V_cell)   (both faces of c along d)
// so sum_f S_f V_cell = C_c (v_c - u_c) = -F_c for ANY u. A face the solver does not solve
// (wall, inflow, ghost; all v_y faces in 2-D) gives its half to the other face, as in scheme 3
// (within a cell of such a face the equality then holds only up to O(h grad u)). Model B: the
// buoyancy terms pres_i of the particles of c go the same way, f_face -= pres_i / (2 V_cell).
//   Scheme 2 [Zhu07 §3.2; Chang08 eq. 2.11]: F_c is distributed to the particles of c by
//     surface area: drag_i = s_i F_c, s_i = d_i^2 / sum_{j in c} d_j^2; coeff[i] = s_i C_c,
//     u_i = u_c, eps[i] = eps_c. Newton's third law holds to round-off (away from walls), also
//     after the gas step (update_particle_forces recomputes u_c with the new gas velocity and
//     keeps C_c, v_c: the exact minus of what the gas received).
//   Scheme 1 [Zhu07 §3.2]: each particle gets its own scheme-3 drag c_i (u_i - v_i), the gas
//     gets -F_c of the cell averages: the third law holds only ON AVERAGE (exactly only when the
//     cell averages reproduce the particles' own state, e.g. identical particles with one
//     velocity in a uniform gas field and porosity). [Zhu07 §3.2] calls it "not reasonable"
//     and lists the early codes (Tsuji 1993, Hoomans 1996) under it. It has their exchange
//     structure, not their models: [Hoomans96 eq. 34-37] gives the particles gravity and a
//     single-particle Wen-Yu force with no pressure force, and the gas a beta from another
//     closure (eq. 45-46); here both sides use one closure and the particles also get the
//     pressure force (docs/coupling.md).
// The pressure force (Model A: -V_i grad p at x_i) or buoyancy term (Model B: -V_i rho_i g) is
// per particle in all three schemes.
#pragma once
#include "coupling/drag/drag_model.hpp"
#include "coupling/interpolation.hpp"
#include "coupling/porosity.hpp"
#include "gas/gas_solver.hpp"
#include "particles/particle_store.hpp"
#include <array>
#include <vector>

namespace fluidem::coupling {

/// InputError for: a bad cube factor, a polydisperse closure without d_mean, a closure a case may
/// not choose (drag::drag_model_refusal: wen_yu_single, a total force, to which this exchange
/// would add the pressure force a second time). Gas Models A and B and schemes 1, 2, 3 are all
/// accepted.
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
  /// 3 i + d, built once per flow step by compute_particle_forces and reused by
  /// deposit_momentum_source and update_particle_forces, which therefore need the particles
  /// at the positions compute_particle_forces saw (as in a flow step: the particles do not move
  /// within it). Empty for the porous cube.
  std::vector<Stencil> face_stencils;
  /// With the stencils: the face pressure differences of the gas pressure the last loop over
  /// the particles read (face_pressure_differences), grid-sized per component.
  std::array<std::vector<double>, 3> face_dp;
  void resize(std::size_t n); ///< every per-particle array n long, zeroed
  /// The per-particle arrays drag_x .. eps.
  std::array<std::vector<double>*, 11> per_particle();
};

/// Sets gs.porosity() (interior cells) from the particles (porosity.hpp).
void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c);
/// The same with caller-kept work space (no allocation once warmed up).
void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c,
                     PorosityScratch& scratch);

/// Gas -> particles: reads gs velocity, pressure, porosity, density and p.x/y/z, vx/vy/vz,
/// radius, mass; writes `out` (and out.scheme = c.scheme; the cell averages for schemes 1, 2).
/// The store is not modified (the integrator adds the forces in its kicks).
void compute_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                             const CouplingSettings& c, ParticleGasForces& out);

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
void deposit_momentum_source(gas::GasSolver& gs, const ParticleStore& p,
                             const ParticleGasForces& f);

/// After the gas step: drag_i = c_i (u_i - v_i) with the coefficients c_i that
/// deposit_momentum_source gave the gas, the NEW gas velocity u_i and the same particle
/// velocities v_i (so that the impulse the particles receive is minus the one the gas received,
/// [Zhu07 §3.2] scheme 3; scheme 1 the same per particle), and the Model A pressure force with
/// the new pressure (Model B: the buoyancy terms are kept, they are what the gas received).
/// Scheme 2: drag_i = s_i C_c (u_c,new - v_c) with the stored C_c, v_c.
void update_particle_forces(const gas::GasSolver& gs, const ParticleStore& p, ParticleGasForces& f);

} // namespace fluidem::coupling
