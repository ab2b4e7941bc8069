// The discretised gas-phase equations (docs/gas.md):
//  continuity [Deen07 eq. 7, Hoomans96 eq. 42], per cell P, backward Euler:
//    V ((eps rho)_P - (eps rho)_P^old) / dt + sum_faces A eps_up rho_up u = 0
//  momentum [Deen07 eq. 8, Zhu07 eq. 5 (A) / eq. 7 (B)], per face, control volume V around it:
//    V ((eps rho)_f u - (eps rho)_f^old u^old) / dt + upwind convection
//      = -c_p A (p_+ - p_-) + div(eps mu grad u) + V (eps rho)_f g + V (K_us - K u + f)
//    with c_p = eps_f (Model A) or 1 (Model B); the viscous term is the Laplacian part of
//    div(eps tau) of [Deen07 eq. 9] (see docs/gas.md for what is neglected);
//  SIMPLEC pressure correction: u' = d (p'_- - p'_+), d = c_p A / (a_P - sum a_nb), and
//    psi eps_P V / dt p'_P + sum_f (eps rho)_up A d (p'_P - p'_nb) = -(mass residual of P).
#include "core/error.hpp"
#include "gas/gas_solver.hpp"
#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>

namespace fluidem::gas {

namespace {
std::vector<double>& slot(StencilSystem& s, int e, int side) {
  switch (2 * e + side) {
  case 0:
    return s.xm;
  case 1:
    return s.xp;
  case 2:
    return s.ym;
  case 3:
    return s.yp;
  case 4:
    return s.zm;
  default:
    return s.zp;
  }
}
} // namespace

void GasSolver::throw_linear_failure(const std::string& what, const LinearSolveStats& st) const {
  std::ostringstream m;
  m << "gas: the " << what << " did not converge in the step from t = " << step_time_
    << " s: relative residual " << st.relative_residual << " after " << st.iterations
    << " iterations (gas.solver.linear_tolerance " << s_.linear_tolerance
    << ", gas.solver.linear_max_iterations " << s_.linear_max_iterations << ")";
  throw InstabilityError(m.str());
}

void GasSolver::compute_mass_fluxes() {
  // Faces with a role lie in the box c[d] = 0..n_d, other axes 1..n; F stays 0 elsewhere
  // (apart from the periodic images written by fill_periodic).
  for (int d = 0; d < 3; ++d) {
    double* F = F_[d].data();
    const double* u = u_[d].data();
    const double *eps = eps_.data(), *rho = rho_.data(); // (not reloaded after each store to F)
    const unsigned char* role = role_[d].data();
    const double A = g_.face_area(d);
    const long sd = g_.stride[d];
    std::array<int, 3> lo{1, 1, 1};
    lo[d] = 0;
    const auto [k0, k1] = dist_ ? own_planes(d) : std::array<int, 2>{lo[2], g_.n[2]};
    const int ny = g_.n[1] - lo[1] + 1, rows = ny * std::max(k1 - k0 + 1, 0);
    for (int r = 0; r < rows; ++r) {
      const long row = g_.idx(0, lo[1] + r % ny, k0 + r / ny);
      for (long q = row + lo[0]; q <= row + g_.n[0]; ++q) {
        const long up = u[q] >= 0.0 ? q : q + sd;
        F[q] = role[q] == none ? 0.0 : A * eps[up] * rho[up] * u[q];
      }
    }
    fill_periodic_and_halo(F_[d]);
  }
}

void GasSolver::add_plane_sums(int k, double dt, double& sum_abs, double& mass) const {
  const double V = g_.cell_volume();
  double sa = sum_abs, ms = mass; // running sums in registers, not through the references
  for (int j = 1; j <= g_.n[1]; ++j)
    for (int i = 1; i <= g_.n[0]; ++i) {
      const long q = g_.idx(i, j, k);
      double R = V * (eps_[q] * rho_[q] - eps_old_[q] * rho_old_[q]) / dt;
      for (int e = 0; e < 3; ++e) R += F_[e][q] - F_[e][q - g_.stride[e]];
      sa += std::abs(R);
      ms += eps_[q] * rho_[q] * V;
    }
  sum_abs = sa;
  mass = ms;
}

double GasSolver::mass_residual(double dt, double& out_rate) {
  if (shared_) return plane_mass_residual(dt, out_rate);
  double sum_abs = 0.0, mass = 0.0;
  for (int k = 1; k <= g_.n[2]; ++k) add_plane_sums(k, dt, sum_abs, mass);
  out_rate = 0.0;
  for (const DomainFace& f : domain_faces_) out_rate += f.sign * F_[f.d][f.q];
  return sum_abs * dt / mass;
}

// The same sums per z plane (each in the order of the whole-grid loop), then over the planes in
// order: the same bits whichever ranks computed the planes.
double GasSolver::plane_mass_residual(double dt, double& out_rate) {
  const auto planes = static_cast<std::size_t>(g_.padded[2]);
  plane_sums_.assign(3 * planes, 0.0);
  const auto [c0, c1] = own_planes(-1);
  for (int k = c0; k <= c1; ++k) {
    double sum_abs = 0.0, mass = 0.0;
    add_plane_sums(k, dt, sum_abs, mass);
    plane_sums_[3 * static_cast<std::size_t>(k)] = sum_abs;
    plane_sums_[3 * static_cast<std::size_t>(k) + 1] = mass;
  }
  const std::array<std::array<int, 2>, 3> own{own_planes(0), own_planes(1), own_planes(2)};
  for (const DomainFace& f : domain_faces_) {
    const long k = f.q / g_.stride[2];
    if (k >= own[f.d][0] && k <= own[f.d][1])
      plane_sums_[3 * static_cast<std::size_t>(k) + 2] += f.sign * F_[f.d][f.q];
  }
  slabs_.gather(plane_sums_.data(), 3);
  double sum_abs = 0.0, mass = 0.0;
  out_rate = 0.0;
  for (std::size_t k = 0; k < planes; ++k) {
    sum_abs += plane_sums_[3 * k];
    mass += plane_sums_[3 * k + 1];
    out_rate += plane_sums_[3 * k + 2];
  }
  return sum_abs * dt / mass;
}

// Incompressible flow without a prescribed pressure: scale the continuous-outflow faces so the
// net volume balance of the domain closes (otherwise the pressure correction has no solution).
void GasSolver::balance_outflow(double dt) {
  const double V = g_.cell_volume();
  double net_in = 0.0, out = 0.0, cap = 0.0;
  for (int k = 1; k <= g_.n[2]; ++k)
    for (int j = 1; j <= g_.n[1]; ++j)
      for (int i = 1; i <= g_.n[0]; ++i) {
        const long q = g_.idx(i, j, k);
        net_in -= V * (eps_[q] * rho_[q] - eps_old_[q] * rho_old_[q]) / dt;
      }
  for (int d = 0; d < 3; ++d) {
    if (bc_.periodic(d)) continue;
    for (std::size_t q = 0; q < F_[d].size(); ++q) {
      if (role_[d][q] == none) continue;
      const long id = (static_cast<long>(q) / g_.stride[d]) % g_.padded[d];
      if (id != 0 && id != g_.n[d]) continue;
      const double sign = id == 0 ? -1.0 : 1.0; // outward
      if (role_[d][q] == outflow) {
        out += sign * F_[d][q];
        const long in = id == 0 ? static_cast<long>(q) + g_.stride[d] : static_cast<long>(q);
        cap += eps_[in] * rho_[in] * g_.face_area(d);
      } else {
        net_in -= sign * F_[d][q];
      }
    }
  }
  const bool scale = std::abs(out) > 1e-12 * std::max(std::abs(net_in), 1e-300);
  for (int d = 0; d < 3; ++d)
    for (std::size_t q = 0; q < F_[d].size(); ++q) {
      if (role_[d][q] != outflow) continue;
      const long id = (static_cast<long>(q) / g_.stride[d]) % g_.padded[d];
      if (scale)
        u_[d][q] *= net_in / out;
      else
        u_[d][q] = (id == 0 ? -1.0 : 1.0) * net_in / cap;
    }
}

// One function of about 200 lines on purpose: its rows are the flow step's hot loop, and the
// fields it reads are taken into locals once for them (bench/gas_bench.cpp measures it).
void GasSolver::solve_momentum(int d, double dt) {
  const double V = g_.cell_volume(), Ad = g_.face_area(d), mu = s_.viscosity;
  const double alpha = s_.velocity_relaxation;
  const long sd = g_.stride[d];
  const int nd = g_.n[d];
  const bool per_d = bc_.periodic(d);
  const bool two_d = g_.dimension == 2;
  std::vector<double>& u = u_[d];
  // Everything the rows read, in locals: the rows' stores (through pointers into vectors) would
  // otherwise make the compiler reload the members after each of them.
  double* const slots[6] = {sys_.xm.data(), sys_.xp.data(), sys_.ym.data(),
                            sys_.yp.data(), sys_.zm.data(), sys_.zp.data()};
  double* const diag = sys_.diag.data();
  double* const rhs_out = sys_.rhs.data();
  double* const dcoef = dcoef_[d].data();
  const double* const uu = u.data();
  const double* const u_old = u_old_[d].data();
  const double* const eps = eps_.data();
  const double* const rho = rho_.data();
  const double* const eps_old = eps_old_.data();
  const double* const rho_old = rho_old_.data();
  const double* const p = p_.data();
  const double* const K = K_[d].data();
  const double* const Kus = Kus_[d].data();
  const double* const fsrc = f_[d].data();
  const unsigned char* const role = role_[d].data();
  const double* const F[3] = {F_[0].data(), F_[1].data(), F_[2].data()};
  const long stride[3] = {g_.stride[0], g_.stride[1], g_.stride[2]};
  const int n[3] = {g_.n[0], g_.n[1], g_.n[2]};
  const bool periodic[3] = {bc_.periodic(0), bc_.periodic(1), bc_.periodic(2)};
  const double area[3] = {g_.face_area(0), g_.face_area(1), g_.face_area(2)};
  const double h[3] = {g_.h[0], g_.h[1], g_.h[2]};
  const double gd = s_.gravity[d];
  const bool model_a = s_.model == PressureModel::A;
  const long sx = g_.stride[0], sy = g_.stride[1], sz = g_.stride[2];
  // One row: face (i, j, k) of component d. Kind 1, interior: every link of the face stays
  // inside the domain (or wraps around a periodic axis) and no boundary face is involved: the
  // same arithmetic without the boundary tests. Kind 2: interior along x and z of a 3-D box one
  // cell deep between walls in y (the pseudo-2-D beds): both y links end at a wall, as the
  // boundary path finds for them, the rest as in the interior. Kind 0: any face.
  const auto row = [&]<int Kind, int Dir>(int i, int j, int k) {
    static_assert(Dir >= 0 && Dir < 3 && Kind >= 0 && Kind <= 2);
    constexpr bool interior = Kind != 0; // along Dir, and along x and z
    const long q = i * sx + j * sy + k * sz;
    if constexpr (!interior) {
      const unsigned char r = role[q];
      if (r == fixed || r == inflow || r == outflow) {
        diag[q] = 1.0;
        rhs_out[q] = uu[q];
        for (double* sl : slots) sl[q] = 0.0;
        dcoef[q] = 0.0;
        return;
      }
    }
    const int c[3] = {i, j, k};
    const int id = c[Dir];
    const long c0 = q, c1 = q + sd;
    const double eps_f = 0.5 * (eps[c0] + eps[c1]);
    const double er = 0.5 * (eps[c0] * rho[c0] + eps[c1] * rho[c1]);
    const double er_old = 0.5 * (eps_old[c0] * rho_old[c0] + eps_old[c1] * rho_old[c1]);
    const double cp = model_a ? eps_f : 1.0;
    double aP = er * V / dt + K[q] * V;
    const double rhs = er_old * V / dt * u_old[q] + (Kus[q] + fsrc[q]) * V + er * V * gd -
                       cp * Ad * (p[c1] - p[c0]);
    double sum_nb = 0.0;
    double nb[6];
#pragma GCC unroll 3
    for (int e = 0; e < 3; ++e) {
      if (two_d && e == 1) { // no flow and free slip across y in 2-D
        nb[2] = nb[3] = 0.0;
        continue;
      }
      const long se = stride[e];
      const double Ae = area[e];
#pragma GCC unroll 2
      for (int side = 0; side < 2; ++side) {
        const int s = side == 0 ? -1 : 1;
        double Fv = 0.0, D = 0.0, gfac = 0.0;
        bool link = true;
        if (e == Dir) {
          const long cell = s < 0 ? c0 : c1;
          double Fa = 0.0, Fb = F[Dir][cell];
          if constexpr (interior) {
            Fa = F[Dir][cell - sd];
          } else { // the face below face 0 is not stored (index -1 along z): not read
            Fa = !per_d && s < 0 && id == 0 ? Fb : F[Dir][cell - sd];
            if (!per_d && s > 0 && id == nd) Fb = Fa;
          }
          Fv = 0.5 * (Fa + Fb);
          D = mu * eps[cell] * Ad / h[Dir];
          if constexpr (!interior) {
            if (!per_d && (id + s < 0 || id + s > nd)) {
              link = false;
              gfac = 1.0; // zero gradient beyond a prescribed-pressure boundary face
            }
          }
        } else {
          const long f0 = s > 0 ? c0 : c0 - se, f1 = s > 0 ? c1 : c1 - se;
          double F0 = F[e][f0], F1 = F[e][f1];
          if constexpr (!interior) {
            if (!per_d && id == 0) F0 = F1;
            if (!per_d && id == nd) F1 = F0;
          }
          Fv = 0.5 * (F0 + F1);
          const double eps_l = 0.25 * (eps[c0] + eps[c1] + eps[c0 + s * se] + eps[c1 + s * se]);
          D = mu * eps_l * Ae / h[e];
          if (!interior || (Kind == 2 && e == 1)) {
            const int ie = c[e] + s;
            if (!periodic[e] && (ie < 1 || ie > n[e])) {
              link = false;
              const int cd = std::clamp(id, 1, nd); // the interior cell next to the face
              gfac = bc_.tangential_factor_at(2 * e + side, Dir == 0 ? cd : i, Dir == 1 ? cd : j,
                                              Dir == 2 ? cd : k);
            }
          }
        }
        const double Fout = s * Fv;
        const double anb = D + std::max(-Fout, 0.0);
        aP += D + std::max(Fout, 0.0);
        if (link) {
          nb[2 * e + side] = -anb;
          sum_nb += anb;
        } else {
          nb[2 * e + side] = 0.0;
          aP -= gfac * anb;
        }
      }
    }
    const double aPr = aP / alpha;
    for (int m = 0; m < 6; ++m) slots[m][q] = nb[m];
    diag[q] = aPr;
    rhs_out[q] = rhs + (1.0 - alpha) * aPr * uu[q];
    dcoef[q] = cp * Ad / std::max(aPr - sum_nb, 1e-6 * aPr);
  };
  // The box of unknowns and, per axis, the index range of interior faces.
  const std::array<int, 3> lo = momentum_box_lo(d);
  std::array<int, 3> in_lo{}, in_hi{};
  for (int a = 0; a < 3; ++a) {
    if (a == d) {
      in_lo[a] = 1;
      in_hi[a] = per_d ? nd : nd - 1;
    } else if ((two_d && a == 1) || bc_.periodic(a)) {
      in_lo[a] = 1;
      in_hi[a] = g_.n[a];
    } else {
      in_lo[a] = 2;
      in_hi[a] = g_.n[a] - 1;
    }
  }
  // A 3-D box one cell deep between y boundaries (pseudo-2-D beds): no row is interior in y,
  // but the rows interior in x and z take the Kind 2 row (both y links at the wall).
  const bool one_cell_in_y = !two_d && g_.n[1] == 1 && !bc_.periodic(1) && d != 1;
  // This rank's rows: its z planes of the box when the ranks share the solve (the Gauss-Seidel
  // solver reads no other row of the system).
  RedBlackGaussSeidel& gs = *momentum_gs_[d];
  const int ny = g_.n[1] - lo[1] + 1;
  const int r_begin = (gs.plane_lo() - lo[2]) * ny,
            r_end = std::max(r_begin, (gs.plane_hi() + 1 - lo[2]) * ny);
  const auto assemble_row = [&](int r) {
    const int j = lo[1] + r % ny, k = lo[2] + r / ny;
    const bool inside_z = k >= in_lo[2] && k <= in_hi[2];
    const bool inside = j >= in_lo[1] && j <= in_hi[1] && inside_z;
    const bool inside_xz = inside || (one_cell_in_y && inside_z);
    const int i0 = inside_xz ? std::max(in_lo[0], lo[0]) : g_.n[0] + 1;
    const int i1 = inside_xz ? in_hi[0] : g_.n[0];
    // The row code of this component (its axis a template argument: the tests on it fold away).
    const auto rows_of = [&]<int Dir>() {
      for (int i = lo[0]; i < i0 && i <= g_.n[0]; ++i) row.template operator()<0, Dir>(i, j, k);
      if (inside)
        for (int i = i0; i <= i1; ++i) row.template operator()<1, Dir>(i, j, k);
      else
        for (int i = i0; i <= i1; ++i) row.template operator()<2, Dir>(i, j, k);
      for (int i = std::max(i1 + 1, i0); i <= g_.n[0]; ++i)
        row.template operator()<0, Dir>(i, j, k);
    };
    if (d == 0)
      rows_of.template operator()<0>();
    else if (d == 1)
      rows_of.template operator()<1>();
    else
      rows_of.template operator()<2>();
  };
  if (parallel_) { // unthreaded: no OpenMP region at all (its runtime call shows on small grids)
#pragma omp parallel for schedule(static)
    for (int r = r_begin; r < r_end; ++r) assemble_row(r);
  } else {
    for (int r = r_begin; r < r_end; ++r) assemble_row(r);
  }
  if (!dist_) gs.gather_planes(dcoef_[d]);
  LinearSolveStats st;
  if (lin_.momentum == LinearSolverOptions::Momentum::gauss_seidel) {
    st = gs.solve(sys_, u, s_.linear_tolerance, lin_.momentum_max_sweeps);
    ++counters_.momentum_solves;
    counters_.momentum_sweeps += st.iterations;
  }
  if (!st.converged) { // hypre GMRES + PFMG, from where Gauss-Seidel stopped
    // Shared, hypre (on this process alone) needs the whole system: every rank's planes.
    for (auto* a :
         {&sys_.diag, &sys_.xm, &sys_.xp, &sys_.ym, &sys_.yp, &sys_.zm, &sys_.zp, &sys_.rhs})
      gs.gather_planes(*a);
    if (dist_) gs.gather_planes(u); // the guess: where Gauss-Seidel stopped, on every plane
    if (!momentum_solver_[d]) {
      StructSolverOptions o;
      o.relax_type = 3; // red-black Gauss-Seidel, non-symmetric
      const std::array<bool, 3> per{bc_.periodic(0), bc_.periodic(1), bc_.periodic(2)};
      momentum_solver_[d] =
          std::make_unique<StructLinearSolver>(g_.padded, momentum_box_lo(d), g_.n, per, false, o);
    }
    st = momentum_solver_[d]->solve(sys_, u, s_.linear_tolerance, s_.linear_max_iterations);
    ++counters_.momentum_fallbacks;
  }
  if (!st.converged)
    throw_linear_failure("momentum equation of velocity component " + std::string(1, "xyz"[d]), st);
  fill_periodic_and_halo(u);
  fill_periodic_and_halo(dcoef_[d]);
}

void GasSolver::solve_pressure_correction(double dt) {
  const double V = g_.cell_volume();
  const double area[3] = {g_.face_area(0), g_.face_area(1), g_.face_area(2)};
  // The rows the solve reads: all, or (shared by ranks, docs/parallel.md) this rank's part.
  std::array<int, 3> rows_lo{1, 1, 1}, rows_hi{g_.n[0], g_.n[1], g_.n[2]};
  if (!pressure_solver_->reads_whole_system()) {
    rows_lo = pressure_solver_->part_lo();
    rows_hi = pressure_solver_->part_hi();
  }
  // Everything the rows read and write, in locals: the rows' stores through the system's
  // arrays would otherwise make the compiler reload the members after each of them.
  const double *eps = eps_.data(), *rho = rho_.data(), *eps_old = eps_old_.data(),
               *rho_old = rho_old_.data();
  const double* F[3] = {F_[0].data(), F_[1].data(), F_[2].data()};
  const double* vel[3] = {u_[0].data(), u_[1].data(), u_[2].data()};
  const double* dcoef[3] = {dcoef_[0].data(), dcoef_[1].data(), dcoef_[2].data()};
  const unsigned char* roles[3] = {role_[0].data(), role_[1].data(), role_[2].data()};
  double* slots[3][2] = {{slot(sys_, 0, 0).data(), slot(sys_, 0, 1).data()},
                         {slot(sys_, 1, 0).data(), slot(sys_, 1, 1).data()},
                         {slot(sys_, 2, 0).data(), slot(sys_, 2, 1).data()}};
  double *sys_diag = sys_.diag.data(), *sys_rhs = sys_.rhs.data();
  const long stride[3] = {g_.stride[0], g_.stride[1], g_.stride[2]};
  const double psi = psi_;
  const auto assemble = [&](int k, int j) {
    for (int i = rows_lo[0]; i <= rows_hi[0]; ++i) {
      const long q = g_.idx(i, j, k);
      double R = V * (eps[q] * rho[q] - eps_old[q] * rho_old[q]) / dt;
      double diag = psi * eps[q] * V / dt;
      for (int e = 0; e < 3; ++e) {
        const long se = stride[e];
        R += F[e][q] - F[e][q - se];
        for (int side = 0; side < 2; ++side) {
          const long f = side == 1 ? q : q - se;
          const unsigned char r = roles[e][f];
          slots[e][side][q] = 0.0;
          if (r != solved && r != periodic_copy && r != pressure_face) continue;
          const long up = vel[e][f] >= 0.0 ? f : f + se;
          const double c = eps[up] * rho[up] * area[e] * dcoef[e][f];
          if (r == pressure_face) {
            diag += 2.0 * c; // p'_ghost = -p'_P: the pressure on the face is fixed
          } else {
            diag += c;
            slots[e][side][q] = -c;
          }
        }
      }
      sys_diag[q] = diag;
      sys_rhs[q] = -R;
    }
  };
  if (parallel_) { // unthreaded: no OpenMP region at all
#pragma omp parallel for collapse(2) schedule(static)
    for (int k = rows_lo[2]; k <= rows_hi[2]; ++k)
      for (int j = rows_lo[1]; j <= rows_hi[1]; ++j) assemble(k, j);
  } else {
    for (int k = rows_lo[2]; k <= rows_hi[2]; ++k)
      for (int j = rows_lo[1]; j <= rows_hi[1]; ++j) assemble(k, j);
  }
  const bool assembled_first = rows_lo[0] == 1 && rows_lo[1] == 1 && rows_lo[2] == 1 &&
                               rows_hi[0] >= 1 && rows_hi[1] >= 1 && rows_hi[2] >= 1; // (1, 1, 1)
  if (!compressible_ && !bc_.any_pressure() && assembled_first) {
    // Pressure fixed up to a constant: pin the level by doubling one diagonal (the system is
    // consistent, so its solution with p'(1,1,1) = 0 is unchanged).
    const long q0 = g_.idx(1, 1, 1);
    sys_.diag[q0] = sys_.diag[q0] > 0.0 ? 2.0 * sys_.diag[q0] : 1.0;
  }
  const auto [q0, q1] = current_range(); // the part the solve writes and its halo planes
  std::fill(pc_.begin() + q0, pc_.begin() + q1, 0.0);
  const auto t0 = std::chrono::steady_clock::now();
  const LinearSolveStats st =
      pressure_solver_->solve(sys_, pc_, s_.linear_tolerance, s_.linear_max_iterations);
  counters_.pressure_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ++counters_.pressure_solves;
  counters_.pressure_iterations += st.iterations;
  counters_.pressure_setups += st.setups;
  if (!st.converged) throw_linear_failure("pressure-correction equation", st);
  // Ghost corrections: prescribed pressure -> -p'_interior, otherwise copy (unused).
  for (const FaceCopy& c : pc_ghosts_) pc_[c.dst] = c.factor * pc_[c.src];
  fill_periodic_and_halo(pc_);
  const double ap = s_.pressure_relaxation;
  const auto [c0, c1] = own_planes(-1);
  for (int k = c0; k <= c1; ++k)
    for (int j = 1; j <= g_.n[1]; ++j)
      for (int i = 1; i <= g_.n[0]; ++i) p_[g_.idx(i, j, k)] += ap * pc_[g_.idx(i, j, k)];
  for (int d = 0; d < 3; ++d) { // solved and pressure faces: c[d] = 0..n_d, other axes 1..n
    const long sd = g_.stride[d];
    double* u = u_[d].data();
    const double* dc = dcoef_[d].data();
    const unsigned char* role = role_[d].data();
    std::array<int, 3> lo{1, 1, 1};
    lo[d] = 0;
    const auto [k0, k1] = dist_ ? own_planes(d) : std::array<int, 2>{lo[2], g_.n[2]};
    for (int k = k0; k <= k1; ++k)
      for (int j = lo[1]; j <= g_.n[1]; ++j) {
        const long row = g_.idx(0, j, k);
        for (long q = row + lo[0]; q <= row + g_.n[0]; ++q)
          if (role[q] == solved || role[q] == pressure_face) u[q] += dc[q] * (pc_[q] - pc_[q + sd]);
      }
    fill_periodic_and_halo(u_[d]);
  }
}

} // namespace fluidem::gas
