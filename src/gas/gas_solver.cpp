// Gas solver: set-up, boundary (ghost) values, the pressure-correction loop of one flow step,
// interpolation and bookkeeping. The discretised equations are in gas_equations.cpp.
#include "gas/gas_solver.hpp"
#include "core/error.hpp"
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace fluidem::gas {

namespace {
GasGrid make_grid(const GasSettings& s) {
  std::array<int, 3> n = s.cells;
  std::array<double, 3> lo{s.lo.x, s.lo.y, s.lo.z}, hi{s.hi.x, s.hi.y, s.hi.z};
  if (s.dimension == 2) {
    n[1] = 1;
    hi[1] = lo[1] + s.depth;
  }
  return GasGrid(s.dimension, n, lo, hi);
}
} // namespace

GasSolver::GasSolver(const GasSettings& settings) : s_(settings) {
  validate(s_);
  g_ = make_grid(s_);
  bc_ = BoundaryMap(s_, g_);
  compressible_ = s_.eos == EquationOfState::ideal_gas;
  psi_ = compressible_ ? s_.molar_mass / (gas_constant * s_.temperature) : 0.0;
  const std::size_t n = g_.size();
  eps_.assign(n, 1.0);
  eps_old_.assign(n, 1.0);
  p_.assign(n, s_.initial_pressure);
  pc_.assign(n, 0.0);
  rho_.assign(n, 0.0);
  for (int d = 0; d < 3; ++d) {
    for (auto* a : {&u_[d], &u_old_[d], &u_iter_[d], &K_[d], &Kus_[d], &f_[d], &F_[d], &dcoef_[d]})
      a->assign(n, 0.0);
  }
  sys_.resize(n);
  init_roles();
  build_boundary_lists();
  for (int d = 0; d < 3; ++d)
    for (std::size_t q = 0; q < n; ++q)
      if (role_[d][q] == solved || role_[d][q] == pressure_face || role_[d][q] == periodic_copy)
        u_[d][q] = s_.initial_velocity[d];
  apply_scalar_bcs();
  update_density();
  apply_velocity_bcs(0.0, true);
  set_inflow_ghost_pressures();

  // Linear solvers: cells 1..n (pressure correction), faces of component d along d from 0
  // (non-periodic: the boundary faces are rows too) or 1 (periodic) to n_d.
  std::array<bool, 3> per{bc_.periodic(0), bc_.periodic(1), bc_.periodic(2)};
  const std::array<int, 3> one{1, 1, 1};
  pressure_solver_ =
      std::make_unique<StructLinearSolver>(g_.padded, one, g_.n, per, true, lin_.pressure);
  slabs_ = PlaneSlabs(kThisProcessAlone, 0, 1, g_.n[2], per[2], g_.stride[2]);
  set_parallel_cells(default_parallel_cells);
}

void GasSolver::set_parallel_cells(long assembly, long gauss_seidel) {
  const long cells = static_cast<long>(g_.n[0]) * g_.n[1] * g_.n[2];
  parallel_ = cells >= assembly;
  const std::array<bool, 3> per{bc_.periodic(0), bc_.periodic(1), bc_.periodic(2)};
  for (int d = 0; d < 3; ++d) {
    if (g_.dimension == 2 && d == 1) continue;
    momentum_gs_[d] = std::make_unique<RedBlackGaussSeidel>(g_.padded, momentum_box_lo(d), g_.n,
                                                            per, cells >= gauss_seidel);
    share_momentum_gs(d);
  }
}

void GasSolver::share_momentum_gs(int d) {
  RedBlackGaussSeidel* gs = momentum_gs_[d].get();
  if (!gs || momentum_ranks_.comm == kThisProcessAlone) return;
  if (dist_) {
    gs->share(momentum_ranks_.comm, momentum_ranks_.rank, slabs_.plane_begin());
    gs->set_whole_solution(false);
  } else {
    gs->share(momentum_ranks_.comm, momentum_ranks_.rank, momentum_ranks_.size);
  }
}

void GasSolver::share(const SharedSolve& ranks) {
  shared_ = true;
  const bool scale_outflow = !compressible_ && !bc_.any_pressure() && bc_.any_outflow();
  const bool slabs = !scale_outflow;
  SharedSolve pressure = ranks;
  if (slabs) pressure.parts = {1, 1, ranks.size}; // the parts are the ranks' z planes
  pressure_solver_->share(pressure);
  dist_ = slabs && !pressure_solver_->reads_whole_system();
  if (dist_) {
    pressure.whole_solution = false;
    pressure_solver_->share(pressure);
    slabs_ = PlaneSlabs(ranks.comm, ranks.rank, ranks.size, g_.n[2], bc_.periodic(2), g_.stride[2]);
    if (slabs_.lo() != pressure_solver_->part_lo()[2] ||
        slabs_.hi() != pressure_solver_->part_hi()[2])
      throw std::logic_error("GasSolver::share: the pressure parts are not the ranks' planes");
  }
  momentum_ranks_ = ranks;
  for (int d = 0; d < 3; ++d) share_momentum_gs(d);
}

std::array<int, 2> GasSolver::own_planes(int d) const {
  const int box_lo = d == 2 && !bc_.periodic(2) ? 0 : 1;
  return {slabs_.first() == 0 ? box_lo : slabs_.lo(), slabs_.hi()};
}

void GasSolver::fill_periodic_and_halo(std::vector<double>& a) const {
  if (!dist_) {
    fill_periodic(a);
    return;
  }
  fill_periodic_ghosts(g_, {bc_.periodic(0), bc_.periodic(1), false}, a);
  slabs_.exchange(a);
}

std::array<int, 3> GasSolver::momentum_box_lo(int d) const {
  std::array<int, 3> lo{1, 1, 1};
  lo[d] = bc_.periodic(d) ? 1 : 0;
  return lo;
}

void GasSolver::set_linear_solver_options(const LinearSolverOptions& options) {
  lin_ = options;
  pressure_solver_->set_options(lin_.pressure);
}

GasSolver::~GasSolver() = default;

void GasSolver::sync_old_porosity() {
  apply_scalar_bcs();
  set_inflow_ghost_pressures();
  eps_old_ = eps_;
}

double GasSolver::rho_of_p(double p) const {
  return compressible_ ? psi_ * p : s_.density;
}

std::array<long, 2> GasSolver::current_range() const {
  if (!dist_) return {0, static_cast<long>(g_.size())};
  return {std::max(slabs_.lo() - 1, 0) * g_.stride[2],
          std::min(slabs_.hi() + 2, g_.padded[2]) * g_.stride[2]};
}

void GasSolver::update_density() {
  const auto [q0, q1] = current_range();
  for (long q = q0; q < q1; ++q) rho_[q] = rho_of_p(p_[q]);
}

void GasSolver::init_roles() {
  for (int d = 0; d < 3; ++d) {
    role_[d].assign(g_.size(), none);
    const int nd = g_.n[d];
    for (int k = 0; k < g_.padded[2]; ++k)
      for (int j = 0; j < g_.padded[1]; ++j)
        for (int i = 0; i < g_.padded[0]; ++i) {
          const int c[3] = {i, j, k};
          bool inside = c[d] <= nd;
          for (int e = 0; e < 3; ++e)
            if (e != d) inside = inside && c[e] >= 1 && c[e] <= g_.n[e];
          if (!inside) continue;
          unsigned char r = solved;
          if (g_.dimension == 2 && d == 1) {
            r = fixed;
          } else if (bc_.periodic(d)) {
            r = c[d] == 0 ? periodic_copy : solved;
          } else if (c[d] == 0 || c[d] == nd) {
            switch (bc_.at(2 * d + (c[d] == 0 ? 0 : 1), i, j, k).normal) {
            case NormalRule::pressure:
              r = pressure_face;
              break;
            case NormalRule::outflow:
              r = outflow;
              break;
            case NormalRule::inflow:
              r = inflow;
              break;
            case NormalRule::wall:
            case NormalRule::periodic: // not on a periodic axis (above)
              r = fixed;
              break;
            }
          }
          role_[d][g_.idx(i, j, k)] = r;
        }
  }
}

// The boundary work lists: the same grid sweeps as the original per-call loops, recorded once.
// The rules each boundary type declares (core/gas_boundary/<type>.hpp), one implementation per
// kind of rule [Hoomans96 Table 1, §3.5]. Ghost porosity and pressure (GhostRule): a prescribed
// porosity is the patch's (the distributor's), a prescribed pressure holds 2 p_b - p_interior
// (p_b on the boundary face), the others copy the interior value. Normal velocity (NormalRule):
// outflow faces copy the adjacent interior face, walls 0, inflow faces U(t)/eps_ghost into the
// domain, pressure faces are solved; tangential ghost velocities: factor * interior.
void GasSolver::build_boundary_lists() {
  for (int d = 0; d < 3; ++d) {
    if (bc_.periodic(d)) continue;
    const long sd = g_.stride[d];
    for (int k = 0; k < g_.padded[2]; ++k)
      for (int j = 0; j < g_.padded[1]; ++j)
        for (int i = 0; i < g_.padded[0]; ++i) {
          const int c[3] = {i, j, k};
          if (c[d] != 0 && c[d] != g_.n[d] + 1) continue;
          const bool low = c[d] == 0;
          const long q = g_.idx(i, j, k), in = low ? q + sd : q - sd;
          scalar_ghosts_.push_back({q, in, &bc_.at(2 * d + (low ? 0 : 1), i, j, k)});
        }
  }
  for (int d = 0; d < 3; ++d) {
    const long sd = g_.stride[d];
    for (int k = 0; k <= g_.n[2]; ++k)
      for (int j = 0; j <= g_.n[1]; ++j)
        for (int i = 0; i <= g_.n[0]; ++i) {
          const long q = g_.idx(i, j, k);
          const unsigned char r = role_[d][q];
          if (r != fixed && r != inflow && r != outflow) continue;
          const int c[3] = {i, j, k};
          const bool low = c[d] == 0;
          if (r == outflow) {
            if (g_.n[d] > 1) outflow_copies_[d].push_back({q, low ? q + sd : q - sd, 1.0});
            continue;
          }
          const BoundaryPatch* in_patch = nullptr;
          if (r == inflow) in_patch = &bc_.at(2 * d + (low ? 0 : 1), i, j, k);
          fixed_faces_[d].push_back({q, in_patch, low ? 1.0 : -1.0});
        }
    for (int e = 0; e < 3; ++e) {
      if (e == d || bc_.periodic(e)) continue;
      const long se = g_.stride[e];
      for (int k = 0; k < g_.padded[2]; ++k)
        for (int j = 0; j < g_.padded[1]; ++j)
          for (int i = 0; i < g_.padded[0]; ++i) {
            const int c[3] = {i, j, k};
            if (c[e] != 0 && c[e] != g_.n[e] + 1) continue;
            const bool low = c[e] == 0;
            const long q = g_.idx(i, j, k);
            const BoundaryPatch& b = bc_.at(2 * e + (low ? 0 : 1), i, j, k);
            tangential_ghosts_[d].push_back({q, low ? q + se : q - se, b.tangential});
          }
    }
  }
  for (int d = 0; d < 3; ++d) {
    if (bc_.periodic(d)) continue;
    const long sd = g_.stride[d];
    for (int k = 1 - (d == 2 ? 1 : 0); k <= g_.n[2] + (d == 2 ? 1 : 0); ++k)
      for (int j = 1 - (d == 1 ? 1 : 0); j <= g_.n[1] + (d == 1 ? 1 : 0); ++j)
        for (int i = 1 - (d == 0 ? 1 : 0); i <= g_.n[0] + (d == 0 ? 1 : 0); ++i) {
          const int c[3] = {i, j, k};
          if (c[d] != 0 && c[d] != g_.n[d] + 1) continue;
          const bool low = c[d] == 0;
          const long q = g_.idx(i, j, k), in = low ? q + sd : q - sd;
          const bool dirichlet =
              bc_.at(2 * d + (low ? 0 : 1), i, j, k).pressure_rule == GhostRule::prescribed;
          pc_ghosts_.push_back({q, in, dirichlet ? -1.0 : 1.0});
        }
  }
  for (int d = 0; d < 3; ++d) {
    if (bc_.periodic(d)) continue;
    for (std::size_t q = 0; q < g_.size(); ++q) {
      if (role_[d][q] == none) continue;
      const long id = (static_cast<long>(q) / g_.stride[d]) % g_.padded[d];
      if (id == 0) domain_faces_.push_back({d, static_cast<long>(q), -1.0});
      if (id == g_.n[d]) domain_faces_.push_back({d, static_cast<long>(q), 1.0});
    }
  }
  // The scalar ghosts along another axis whose source lies in the ghost layer of an axis with
  // inflow faces (set_inflow_ghost_pressures), in the order apply_scalar_bcs fills them.
  std::array<bool, 3> inflow_axis{};
  for (int d = 0; d < 3; ++d)
    for (const FixedFace& f : fixed_faces_[d]) inflow_axis[d] = inflow_axis[d] || f.inflow;
  for (std::size_t k = 0; k < scalar_ghosts_.size(); ++k) {
    const ScalarGhost& sg = scalar_ghosts_[k];
    const long step = sg.q > sg.in ? sg.q - sg.in : sg.in - sg.q;
    bool in_layer = false;
    for (int d = 0; d < 3; ++d) {
      if (!inflow_axis[d] || step == g_.stride[d]) continue;
      const long cd = (sg.in / g_.stride[d]) % g_.padded[d];
      in_layer = in_layer || cd == 0 || cd == g_.n[d] + 1;
    }
    if (in_layer) inflow_layer_ghosts_.push_back(k);
  }
}

void GasSolver::fill_periodic(std::vector<double>& a) const {
  fill_periodic_ghosts(g_, {bc_.periodic(0), bc_.periodic(1), bc_.periodic(2)}, a);
}

void fill_periodic_ghosts(const GasGrid& g, const std::array<bool, 3>& periodic,
                          std::vector<double>& a) {
  for (int d = 0; d < 3; ++d) { // the ghost layer c[d] = 0 and n + 1 (whole layers: edges too)
    if (!periodic[d]) continue;
    const long sd = g.stride[d], nd = g.n[d];
    const int a1 = d == 0 ? 1 : 0, a2 = d == 2 ? 1 : 2; // the other two axes
    for (int c2 = 0; c2 < g.padded[a2]; ++c2)
      for (int c1 = 0; c1 < g.padded[a1]; ++c1) {
        const long q = c1 * g.stride[a1] + c2 * g.stride[a2];
        a[q] = a[q + nd * sd];
        a[q + (nd + 1) * sd] = a[q + sd];
      }
  }
}

// Ghost porosity and pressure [Hoomans96 §3.5], by the patch's GhostRule: prescribed porosity
// (inflow: the distributor's) or a copy of the interior; prescribed pressure 2 p_b - p_interior
// (p_b on the boundary face) or a copy of the interior.
void GasSolver::apply_scalar_bcs() {
  for (const ScalarGhost& g : scalar_ghosts_) {
    const BoundaryPatch& b = *g.patch;
    eps_[g.q] = b.porosity_rule == GhostRule::prescribed ? b.porosity : eps_[g.in];
    p_[g.q] = b.pressure_rule == GhostRule::prescribed ? 2.0 * b.pressure - p_[g.in] : p_[g.in];
  }
  fill_periodic(eps_); // every rank's porosity is whole
  fill_periodic_and_halo(p_);
}

void GasSolver::apply_velocity_bcs(double t_new, bool set_inflow) {
  for (int d = 0; d < 3; ++d) {
    std::vector<double>& u = u_[d];
    for (const FaceCopy& c : outflow_copies_[d]) u[c.dst] = u[c.src];
    if (set_inflow)
      for (const FixedFace& f : fixed_faces_[d]) {
        u[f.q] = 0.0;
        if (f.inflow)
          u[f.q] = f.sign * inflow_velocity(f.inflow->inflow, t_new) / f.inflow->porosity;
      }
    // Tangential ghost velocities (used only by interpolation): factor * interior.
    for (const FaceCopy& c : tangential_ghosts_[d]) u[c.dst] = c.factor * u[c.src];
    fill_periodic_and_halo(u);
  }
}

void GasSolver::step(double time, double dt) {
  if (!(dt > 0.0) || !std::isfinite(dt) || !std::isfinite(time))
    throw InputError("gas: flow time step dt must be > 0 s (got " + std::to_string(dt) + ")");
  const double t_new = time + dt;
  step_time_ = time;
  pressure_solver_->new_step();
  u_old_ = u_;
  apply_scalar_bcs();
  update_density();
  rho_old_ = rho_;
  apply_velocity_bcs(t_new, true);
  const bool scale_outflow = !compressible_ && !bc_.any_pressure() && bc_.any_outflow();

  double res = 0.0, dv = 0.0, dv_err = 0.0, out_rate = 0.0;
  double dv_prev = 0.0, ratio_prev = 0.0;
  int it = 0;
  bool converged = false;
  while (it < s_.max_iterations && !converged) {
    ++it;
    const auto [first, last] = current_range(); // all that the convergence test reads
    for (int d = 0; d < 3; ++d)
      std::copy(u_[d].begin() + first, u_[d].begin() + last, u_iter_[d].begin() + first);
    // From the second iteration on, the fluxes of the last one's end still hold: u, eps and
    // rho have not changed since.
    if (it == 1) compute_mass_fluxes();
    for (int d = 0; d < 3; ++d)
      if (momentum_gs_[d]) solve_momentum(d, dt);
    apply_velocity_bcs(t_new, false);
    compute_mass_fluxes();
    if (scale_outflow) {
      balance_outflow(dt);
      compute_mass_fluxes();
    }
    solve_pressure_correction(dt);
    apply_scalar_bcs();
    update_density();
    apply_velocity_bcs(t_new, false);
    compute_mass_fluxes();
    res = mass_residual(dt, out_rate);
    dv = 0.0;
    for (int d = 0; d < 3; ++d) {
      const auto [k0, k1] = dist_ ? own_planes(d) : std::array<int, 2>{0, g_.padded[2] - 1};
      const auto q1 = static_cast<std::size_t>((k1 + 1) * g_.stride[2]);
      // Four running maxima in registers (a maximum does not depend on the order): one chain
      // of dependent maxima through dv in memory was a tenth of the 2-D demo's gas step.
      const unsigned char* role = role_[d].data();
      const double *u = u_[d].data(), *u_it = u_iter_[d].data();
      double m[4] = {dv, 0.0, 0.0, 0.0};
      auto q = static_cast<std::size_t>(k0 * g_.stride[2]);
      for (; q + 4 <= q1; q += 4)
        for (std::size_t l = 0; l < 4; ++l)
          if (role[q + l] != none) m[l] = std::max(m[l], std::abs(u[q + l] - u_it[q + l]));
      for (; q < q1; ++q)
        if (role[q] != none) m[0] = std::max(m[0], std::abs(u[q] - u_it[q]));
      dv = std::max(std::max(m[0], m[1]), std::max(m[2], m[3]));
    }
    if (dist_) dv = slabs_.max(dv);
    if (!std::isfinite(res) || !std::isfinite(dv)) {
      std::ostringstream m;
      m << "gas: NaN in the flow solution in the step from t = " << time << " s to " << t_new
        << " s (iteration " << it << ")";
      throw InstabilityError(m.str());
    }
    // The velocity's distance from the converged solution: the iterations contract
    // (u_k - u*) by a ratio r per iteration, so |u_k - u*| <= r / (1 - r) |u_k - u_{k-1}|
    // [the a-posteriori bound of a contraction]; r is estimated from the last two changes
    // (the larger of the last two ratios, so from the third iteration on). Used only when it
    // is tighter than the change itself (r < 1/2): never stricter than the plain change test.
    dv_err = dv;
    const double ratio = it >= 2 && dv_prev > 0.0 ? dv / dv_prev : 1.0;
    const double r = std::max(ratio, ratio_prev);
    if (it >= 3 && r < 0.5) dv_err = dv * r / (1.0 - r);
    ratio_prev = ratio;
    dv_prev = dv;
    converged = res < s_.tolerance && dv_err < s_.velocity_tolerance;
  }
  last_iterations_ = it;
  last_mass_residual_ = res;
  last_velocity_change_ = dv;
  boundary_outflow_ = out_rate;
  if (!converged) {
    std::ostringstream m;
    m << "gas: pressure-correction iterations did not converge in the step from t = " << time
      << " s to " << t_new << " s: after " << it << " iterations (gas.solver.max_iterations) "
      << "mass residual " << res << " (gas.solver.tolerance " << s_.tolerance
      << "), velocity change " << dv << " m/s, estimated velocity error " << dv_err
      << " m/s (gas.solver.velocity_tolerance " << s_.velocity_tolerance << ")";
    throw InstabilityError(m.str());
  }
  set_inflow_ghost_pressures();
  if (dist_) { // the one gather of the step: every rank's planes of the fields kept
    for (std::vector<double>* a : {&u_[0], &u_[1], &u_[2], &p_, &rho_}) {
      slabs_.gather(a->data(), g_.stride[2]);
      fill_periodic(*a);
    }
  }
  eps_old_ = eps_;
}

// [docs/gas.md, "Pressure on an inflow face"]: along the inward normal n = s e_d (s = +1 on a
// low face), the gas of the half cell between the face and the centre of the first cell c,
// steady and without viscous stress, is held by the pressure difference, its weight and the
// particles' force on it (the weights of the particles' stencils that fall on the face, per
// volume of the half cell: twice the face's S per cell volume):
//   c_p (p_b - p_c) = -s (h/2) (2 S_face + eps_c rho_c g_d),  c_p = eps_c (A) or 1 (B)
// [Zhu07 eq. 5, 7]. Convection is left out: the first-order upwind flux into the first
// interior face's volume is the inflow's own (the half cell passes it on unchanged).
double GasSolver::inflow_face_pressure(int d, long q) const {
  const long sd = g_.stride[d];
  const long id = (q / sd) % g_.padded[d];
  const double s = id == 0 ? 1.0 : -1.0;
  const auto c = static_cast<std::size_t>(id == 0 ? q + sd : q);
  const auto uq = static_cast<std::size_t>(q);
  const double S = Kus_[d][uq] - K_[d][uq] * u_[d][uq] + f_[d][uq];
  const double cp = s_.model == PressureModel::A ? eps_[c] : 1.0;
  return p_[c] - s * 0.5 * g_.h[d] * (2.0 * S + eps_[c] * rho_[c] * s_.gravity[d]) / cp;
}

void GasSolver::set_inflow_ghost_pressures() {
  for (int d = 0; d < 3; ++d)
    for (const FixedFace& f : fixed_faces_[d]) {
      if (f.inflow == nullptr) continue;
      const long sd = g_.stride[d];
      const long c = f.sign > 0.0 ? f.q + sd : f.q, ghost = f.sign > 0.0 ? f.q : f.q + sd;
      const double pb = inflow_face_pressure(d, f.q);
      p_[static_cast<std::size_t>(ghost)] = 2.0 * pb - p_[static_cast<std::size_t>(c)];
    }
  // The edge and corner ghosts beside them copy them again, as apply_scalar_bcs would have: a
  // ghost along another axis that copied the old inflow ghost would otherwise make a pressure
  // difference across that axis's wall in the ghost layer, a force on the particles whose
  // stencils reach it (it set a disc one particle deep bouncing between its two y walls).
  for (const std::size_t k : inflow_layer_ghosts_) {
    const ScalarGhost& sg = scalar_ghosts_[k];
    const auto q = static_cast<std::size_t>(sg.q), in = static_cast<std::size_t>(sg.in);
    p_[q] = sg.patch->pressure_rule == GhostRule::prescribed ? 2.0 * sg.patch->pressure - p_[in]
                                                             : p_[in];
  }
  fill_periodic(p_);
}

void GasSolver::check_courant(double t_new, double dt) const {
  double worst = 0.0;
  int wd = 0;
  std::size_t wq = 0;
  for (int d = 0; d < 3; ++d) {
    const double f = dt / g_.h[d];
    for (std::size_t q = 0; q < u_[d].size(); ++q)
      if (role_[d][q] != none && std::abs(u_[d][q]) * f > worst) {
        worst = std::abs(u_[d][q]) * f;
        wd = d;
        wq = q;
      }
  }
  if (!(worst > s_.max_courant)) return;
  const long q = static_cast<long>(wq);
  const long i = q % g_.padded[0], j = (q / g_.padded[0]) % g_.padded[1],
             k = q / (static_cast<long>(g_.padded[0]) * g_.padded[1]);
  std::ostringstream m;
  m << "gas: Courant number " << worst << " above gas.solver.max_courant = " << s_.max_courant
    << " at t = " << t_new << " s: velocity component "
    << "xyz"[wd] << " = " << u_[wd][wq] << " m/s on the high face of cell (" << i << ", " << j
    << ", " << k << ") (the gas crosses more than that many cells per flow step DT = " << dt
    << " s; reduce the flow step)";
  throw InstabilityError(m.str());
}

std::vector<double> GasSolver::applied_source(int d) const {
  std::vector<double> s(g_.size(), 0.0);
  for (std::size_t q = 0; q < s.size(); ++q)
    if (role_[d][q] == solved || role_[d][q] == pressure_face || role_[d][q] == inflow)
      s[q] = Kus_[d][q] - K_[d][q] * u_[d][q] + f_[d][q];
  return s;
}

double GasSolver::gas_mass() const {
  double m = 0.0;
  for (int k = 1; k <= g_.n[2]; ++k)
    for (int j = 1; j <= g_.n[1]; ++j)
      for (int i = 1; i <= g_.n[0]; ++i) {
        const long q = g_.idx(i, j, k);
        m += eps_[q] * rho_[q];
      }
  return m * g_.cell_volume();
}

double GasSolver::pressure_at(const Vec3& x) const {
  // Cell-centre lattice including the ghost centres: position in units of cells from the
  // centre of ghost cell 0, clamped to [0, n + 1].
  int i0[3];
  double w[3];
  for (int d = 0; d < 3; ++d) {
    if (g_.dimension == 2 && d == 1) {
      i0[d] = 1;
      w[d] = 0.0;
      continue;
    }
    double s = (x[d] - g_.lo[d]) / g_.h[d] + 0.5;
    s = std::clamp(s, 0.0, static_cast<double>(g_.n[d] + 1));
    int c = std::min(static_cast<int>(s), g_.n[d]);
    i0[d] = c;
    w[d] = s - c;
  }
  double v = 0.0;
  for (int c = 0; c < 8; ++c) {
    const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
    const double wt = (a ? w[0] : 1.0 - w[0]) * (b ? w[1] : 1.0 - w[1]) * (e ? w[2] : 1.0 - w[2]);
    if (wt == 0.0) continue;
    v += wt * p_[g_.idx(i0[0] + a, i0[1] + b, i0[2] + e)];
  }
  return v;
}

} // namespace fluidem::gas

namespace fluidem::gas {

GasSolver::State GasSolver::state() const {
  State st;
  st.u = u_;
  st.p = p_;
  st.eps = eps_;
  st.eps_old = eps_old_;
  st.rho = rho_;
  st.last_iterations = last_iterations_;
  st.last_mass_residual = last_mass_residual_;
  st.last_velocity_change = last_velocity_change_;
  st.boundary_outflow = boundary_outflow_;
  return st;
}

void GasSolver::restore(const State& st) {
  const std::size_t n = g_.size();
  bool ok = st.p.size() == n && st.eps.size() == n && st.eps_old.size() == n && st.rho.size() == n;
  for (int d = 0; d < 3; ++d) ok = ok && st.u[d].size() == n;
  if (!ok)
    throw InputError("gas: the restored state does not fit the grid (" + std::to_string(n) +
                     " padded cells)");
  u_ = st.u;
  p_ = st.p;
  eps_ = st.eps;
  eps_old_ = st.eps_old;
  rho_ = st.rho;
  last_iterations_ = static_cast<int>(st.last_iterations);
  last_mass_residual_ = st.last_mass_residual;
  last_velocity_change_ = st.last_velocity_change;
  boundary_outflow_ = st.boundary_outflow;
}

void GasSolver::reset_solver_history() {
  pressure_solver_->set_options(pressure_solver_->options());
  for (auto& m : momentum_solver_)
    if (m) m->set_options(m->options());
}

} // namespace fluidem::gas
