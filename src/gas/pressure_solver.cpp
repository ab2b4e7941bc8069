// hypre Struct wrapper: PFMG- (or SMG-) preconditioned PCG / GMRES on one box, on one MPI rank or
// shared by several (share()), with the hypre objects kept from solve to solve
// (pressure_solver.hpp).
// Open MPI: C bindings only (the C++ bindings would need libmpi_cxx at link time).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include "gas/pressure_solver.hpp"
#include "core/error.hpp"
#include "gas/band_solver.hpp"
#include "gas/rank_dot.hpp"
#include "gas/shared_pcg.hpp"
#include <HYPRE_struct_ls.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <mpi.h>
#include <mutex>
#include <stdexcept>

namespace fluidem::gas {

void StencilSystem::resize(std::size_t n) {
  for (auto* v : {&diag, &xm, &xp, &ym, &yp, &zm, &zp, &rhs}) v->assign(n, 0.0);
}

namespace {
void finalize_mpi() {
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized) MPI_Finalize();
}
void finalize_hypre() {
  HYPRE_Finalize();
}
} // namespace

void ensure_mpi_initialised() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (!initialised) {
      // Open MPI refuses some set-ups as root only under mpirun; a singleton (no mpirun) works
      // as root here. Keep the singleton from probing network interfaces.
      setenv("OMPI_MCA_btl", "self", 0);
      int provided = 0;
      if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS)
        throw InstabilityError("gas: MPI_Init_thread failed (needed by hypre)");
      std::atexit(finalize_mpi);
    }
    HYPRE_Init();
    std::atexit(finalize_hypre); // registered last, so it runs before MPI_Finalize
  });
}

bool mpi_started() {
  int initialised = 0;
  MPI_Initialized(&initialised);
  return initialised != 0;
}

namespace {
// Krylov preconditioner "set-up" that does nothing: the multigrid set-up is done (or reused)
// by StructLinearSolver itself, not by the Krylov solver's set-up.
HYPRE_Int no_setup(HYPRE_StructSolver, HYPRE_StructMatrix, HYPRE_StructVector, HYPRE_StructVector) {
  return 0;
}
} // namespace

struct StructLinearSolver::Impl {
  std::array<int, 3> padded{}, lo{}, hi{};
  std::array<bool, 3> periodic{}; ///< periodic in hypre (period >= 3)
  std::array<int, 3> fold{};      ///< periodic with period 1 or 2: folded here
  bool symmetric = false;
  int max_levels = 0; ///< PFMG levels that keep every period >= 3 (0: no limit)
  long cells = 0;     ///< unknowns in the box
  // hypre's view: ndim axes (x, z when the box is one cell thick along y, else x, y, z),
  // this rank's extents phlo..phhi (set_part), stencil entries in the order of `slot` (index
  // into the 7 stencil arrays: 0 diag, 1 xm, 2 xp, 3 ym, 4 yp, 5 zm, 6 zp).
  int ndim = 3;
  std::array<int, 7> slot{0, 1, 2, 3, 4, 5, 6};
  int nentries = 7;
  StructSolverOptions opt;
  std::array<int, 3> hperiod{};    ///< hypre's periods per hypre axis (0: not periodic)
  HYPRE_StructGrid grid = nullptr; ///< the hypre objects: made on the first iterative solve
  /// (make_hypre), so that runs whose pressure is solved directly never start MPI (a
  /// singleton MPI_Init spawns Open MPI's daemon: 0.35 s, and 0.05 s to finalize)
  HYPRE_StructStencil stencil = nullptr;
  HYPRE_StructMatrix A = nullptr;
  HYPRE_StructVector b = nullptr, x = nullptr;
  HYPRE_StructSolver krylov = nullptr, mg = nullptr;
  bool step_started = true;       ///< new_step() since the last set-up
  bool stale = true;              ///< adaptive: the set-up should be redone
  int iterations_after_setup = 0; ///< of the first solve after the last set-up
  long n_setups = 0, n_solves = 0, n_direct = 0;
  std::vector<double> values, buf_b, buf_x;

  // Shared solve (share()): this rank's part plo..phi of the box (padded indices; all of it
  // when not shared), its hypre extents, every rank's part, and the vector of matrix products.
  bool shared = false;
  SharedSolve sh;
  std::array<int, 3> plo{}, phi{}, phlo{}, phhi{};
  long part_cells = 0;
  std::vector<std::array<int, 6>> parts; ///< per rank: lo[3], hi[3] (padded indices)
  HYPRE_StructVector y = nullptr;
  std::vector<double> gathered, guess;
  SharedPcgWork work;
  std::vector<int> counts, displs;

  MPI_Comm comm() const { return shared && sh.comm != -1 ? MPI_Comm_f2c(sh.comm) : MPI_COMM_SELF; }
  std::array<int, 3> axis_of_hypre() const {
    return ndim == 2 ? std::array<int, 3>{0, 2, 2} : std::array<int, 3>{0, 1, 2};
  }
  static long count(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    long n = 1;
    for (int d = 0; d < 3; ++d) n *= std::max(0, b[d] - a[d] + 1);
    return n;
  }
  void set_part(std::array<int, 3> l, std::array<int, 3> h) {
    plo = l;
    phi = h;
    part_cells = count(l, h);
    const auto axis = axis_of_hypre();
    for (int a = 0; a < ndim; ++a) {
      phlo[a] = l[axis[a]];
      phhi[a] = h[axis[a]];
    }
  }

  // Direct solver (StructSolverOptions::direct_max_work): the box's unknowns numbered with
  // the longest axis slowest; per band index its padded index, the band offsets of the
  // neighbours along each axis and which of the 6 neighbours are in the box (bit 2 a + side).
  std::unique_ptr<BandCholesky> band;
  bool band_possible = false; ///< symmetric, no periodic axis
  double band_work = 0.0;     ///< multiply-adds of one factorisation
  std::vector<long> band_p;
  std::vector<unsigned char> band_nb;
  std::array<long, 3> band_stride{}; ///< per grid axis (0 for an axis of extent 1)
  std::vector<double> band_b, band_x;

  void make_band() {
    std::array<int, 3> ext{}, order{0, 1, 2};
    for (int d = 0; d < 3; ++d) ext[d] = hi[d] - lo[d] + 1;
    std::stable_sort(order.begin(), order.end(), [&](int a, int c) { return ext[a] < ext[c]; });
    band = std::make_unique<BandCholesky>(
        std::array<int, 3>{ext[order[0]], ext[order[1]], ext[order[2]]});
    long st = 1;
    for (int r = 0; r < 3; ++r) {
      band_stride[order[r]] = ext[order[r]] > 1 ? st : 0;
      st *= ext[order[r]];
    }
    const std::size_t n = band->size();
    band_p.assign(n, 0);
    band_nb.assign(n, 0);
    band_b.assign(n, 0.0);
    band_x.assign(n, 0.0);
    const long sy = padded[0], sz = static_cast<long>(padded[0]) * padded[1];
    for (int k = lo[2]; k <= hi[2]; ++k)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) {
          const int c[3] = {i, j, k};
          long bi = 0;
          unsigned char nb = 0;
          for (int d = 0; d < 3; ++d) {
            bi += (c[d] - lo[d]) * band_stride[d];
            if (c[d] > lo[d]) nb |= static_cast<unsigned char>(1u << (2 * d));
            if (c[d] < hi[d]) nb |= static_cast<unsigned char>(1u << (2 * d + 1));
          }
          band_p[static_cast<std::size_t>(bi)] = i + j * sy + k * sz;
          band_nb[static_cast<std::size_t>(bi)] = nb;
        }
  }

  /// Banded Cholesky solve of sys into x (box entries). False if the factorisation fails (x
  /// untouched) or the residual misses rel_tol (x: the direct solution, a starting guess).
  bool direct_solve(const StencilSystem& sys, std::vector<double>& xv, double rel_tol,
                    LinearSolveStats& st) {
    if (!band) make_band();
    BandCholesky& B = *band;
    const std::size_t n = B.size();
    const std::array<const std::vector<double>*, 3> lower{&sys.xm, &sys.ym, &sys.zm};
    const std::array<const std::vector<double>*, 3> upper{&sys.xp, &sys.yp, &sys.zp};
    B.clear();
    double bb = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto p = static_cast<std::size_t>(band_p[i]);
      B.lower(i, 0) = sys.diag[p];
      for (int d = 0; d < 3; ++d)
        if (band_nb[i] & (1u << (2 * d)))
          B.lower(i, static_cast<int>(band_stride[d])) = (*lower[d])[p];
      band_b[i] = sys.rhs[p];
      bb += band_b[i] * band_b[i];
    }
    if (bb == 0.0) { // x = 0, as hypre's Krylov solvers answer b = 0
      for (std::size_t i = 0; i < n; ++i) xv[static_cast<std::size_t>(band_p[i])] = 0.0;
      st = {1, 0.0, true, 0};
      return true;
    }
    if (!B.factor()) return false;
    B.solve(band_b.data(), band_x.data());
    // The residual with the full stencil (both triangles), as the Krylov solvers measure it.
    double rr = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const auto p = static_cast<std::size_t>(band_p[i]);
      double r = band_b[i] - sys.diag[p] * band_x[i];
      for (int d = 0; d < 3; ++d) {
        const auto s = static_cast<std::size_t>(band_stride[d]);
        if (band_nb[i] & (1u << (2 * d))) r -= (*lower[d])[p] * band_x[i - s];
        if (band_nb[i] & (1u << (2 * d + 1))) r -= (*upper[d])[p] * band_x[i + s];
      }
      rr += r * r;
    }
    st = {1, std::sqrt(rr / bb), false, 0};
    st.converged = st.relative_residual <= rel_tol;
    for (std::size_t i = 0; i < n; ++i) xv[static_cast<std::size_t>(band_p[i])] = band_x[i];
    return st.converged;
  }

  void make_hypre() {
    ensure_mpi_initialised();
    HYPRE_StructGridCreate(comm(), ndim, &grid);
    if (part_cells > 0) HYPRE_StructGridSetExtents(grid, phlo.data(), phhi.data());
    HYPRE_StructGridSetPeriodic(grid, hperiod.data());
    HYPRE_StructGridAssemble(grid);
    HYPRE_StructStencilCreate(ndim, nentries, &stencil);
    for (int e = 0; e < nentries; ++e) {
      std::array<int, 3> offset{0, 0, 0};
      if (e > 0) offset[(e - 1) / 2] = e % 2 == 1 ? -1 : 1; // m, p along hypre axis (e-1)/2
      HYPRE_StructStencilSetElement(stencil, e, offset.data());
    }
    HYPRE_StructMatrixCreate(comm(), grid, stencil, &A);
    HYPRE_StructMatrixInitialize(A);
    HYPRE_StructVectorCreate(comm(), grid, &b);
    HYPRE_StructVectorInitialize(b);
    HYPRE_StructVectorCreate(comm(), grid, &x);
    HYPRE_StructVectorInitialize(x);
    if (shared) {
      HYPRE_StructVectorCreate(comm(), grid, &y);
      HYPRE_StructVectorInitialize(y);
    }
    const auto n = static_cast<std::size_t>(part_cells);
    values.resize(static_cast<std::size_t>(nentries) * n);
    buf_b.resize(n);
    buf_x.resize(n);
  }

  void destroy_mg() {
    if (!mg) return;
    if (opt.multigrid == StructSolverOptions::Multigrid::smg)
      HYPRE_StructSMGDestroy(mg);
    else
      HYPRE_StructPFMGDestroy(mg);
    mg = nullptr;
  }

  // A fresh multigrid preconditioner for the current matrix values, handed to the Krylov solver.
  void setup_mg() {
    destroy_mg();
    if (opt.multigrid == StructSolverOptions::Multigrid::smg) {
      HYPRE_StructSMGCreate(comm(), &mg);
      HYPRE_StructSMGSetMemoryUse(mg, 0);
      HYPRE_StructSMGSetMaxIter(mg, 1);
      HYPRE_StructSMGSetTol(mg, 0.0);
      HYPRE_StructSMGSetZeroGuess(mg);
      HYPRE_StructSMGSetNumPreRelax(mg, opt.pre_relax);
      HYPRE_StructSMGSetNumPostRelax(mg, opt.post_relax);
      HYPRE_StructSMGSetup(mg, A, b, x);
    } else {
      HYPRE_StructPFMGCreate(comm(), &mg);
      HYPRE_StructPFMGSetMaxIter(mg, 1);
      HYPRE_StructPFMGSetTol(mg, 0.0);
      HYPRE_StructPFMGSetZeroGuess(mg);
      HYPRE_StructPFMGSetRelaxType(mg, opt.relax_type);
      HYPRE_StructPFMGSetRAPType(mg, opt.rap_type);
      HYPRE_StructPFMGSetNumPreRelax(mg, opt.pre_relax);
      HYPRE_StructPFMGSetNumPostRelax(mg, opt.post_relax);
      HYPRE_StructPFMGSetSkipRelax(mg, opt.skip_relax);
      int levels = opt.max_levels;
      if (levels <= 0 && opt.min_coarse_cells > 0) { // halve (semi-coarsening) while >= min
        levels = 1;
        for (long c = cells; c / 2 >= opt.min_coarse_cells; c /= 2) ++levels;
      }
      if (max_levels > 0) levels = levels > 0 ? std::min(levels, max_levels) : max_levels;
      if (levels > 0) HYPRE_StructPFMGSetMaxLevels(mg, levels);
      // Shared: the coarsening directions from the whole system (each rank holds it), not from
      // hypre's sums of the coefficients over the ranks, whose rounding depends on the parts.
      if (shared) HYPRE_StructPFMGSetDxyz(mg, dxyz.data());
      HYPRE_StructPFMGSetup(mg, A, b, x);
    }
    if (shared) {
      ++n_setups;
      step_started = false;
      stale = false;
      return; // shared_pcg() is the Krylov solver
    }
    const bool smg = opt.multigrid == StructSolverOptions::Multigrid::smg;
    const HYPRE_PtrToStructSolverFcn solve_fn = smg ? HYPRE_StructSMGSolve : HYPRE_StructPFMGSolve;
    if (!krylov) {
      if (symmetric) {
        HYPRE_StructPCGCreate(MPI_COMM_SELF, &krylov);
        HYPRE_StructPCGSetTwoNorm(krylov, 1);
        HYPRE_StructPCGSetPrecond(krylov, solve_fn, no_setup, mg);
        HYPRE_StructPCGSetup(krylov, A, b, x);
      } else {
        HYPRE_StructGMRESCreate(MPI_COMM_SELF, &krylov);
        HYPRE_StructGMRESSetKDim(krylov, 30);
        HYPRE_StructGMRESSetPrecond(krylov, solve_fn, no_setup, mg);
        HYPRE_StructGMRESSetup(krylov, A, b, x);
      }
    } else if (symmetric) {
      HYPRE_StructPCGSetPrecond(krylov, solve_fn, no_setup, mg);
    } else {
      HYPRE_StructGMRESSetPrecond(krylov, solve_fn, no_setup, mg);
    }
    ++n_setups;
    step_started = false;
    stale = false;
  }

  // Shared: hypre's coarsening weights per hypre axis, 1/sqrt(mean over the whole box of the
  // |off-diagonal| coefficients along it) (the measure hypre's PFMG computes itself, taken here
  // from the whole system in one order, so that every rank and every number of ranks coarsens
  // alike); an axis without links is never coarsened.
  std::array<double, 3> dxyz{1.0, 1.0, 1.0};
  void set_dxyz(const StencilSystem& sys) {
    const std::array<const std::vector<double>*, 6> off{&sys.xm, &sys.xp, &sys.ym,
                                                        &sys.yp, &sys.zm, &sys.zp};
    const long sy = padded[0], sz = static_cast<long>(padded[0]) * padded[1];
    // The sums of |links| per axis over the whole box, from this rank's part summed over the
    // ranks in fixed point (rank_dot.hpp): the same bits for any parts, and no rank reads rows
    // outside its part.
    std::array<double, 3> c{};
    std::vector<double> links;
    links.reserve(2 * static_cast<std::size_t>(part_cells));
    for (int d = 0; d < 3; ++d) {
      links.clear();
      for (int k = plo[2]; k <= phi[2]; ++k)
        for (int j = plo[1]; j <= phi[1]; ++j)
          for (int i = plo[0]; i <= phi[0]; ++i) {
            const auto p = static_cast<std::size_t>(i + j * sy + k * sz);
            links.push_back(std::abs((*off[2 * d])[p]));
            links.push_back(std::abs((*off[2 * d + 1])[p]));
          }
      const std::vector<double> ones(links.size(), 1.0);
      c[static_cast<std::size_t>(d)] =
          rank_dot(sh.comm, 2 * cells, links.data(), ones.data(), links.size());
    }
    const auto axis = axis_of_hypre();
    dxyz = {1.0, 1.0, 1.0};
    for (int h = 0; h < ndim; ++h) {
      const double mean = c[axis[h]] / static_cast<double>(cells);
      dxyz[h] = mean > 0.0 ? 1.0 / std::sqrt(mean) : 1e100;
    }
  }

  // Shared: PCG on this rank's part (xs: its part of the initial guess, then the solution).
  LinearSolveStats shared_solve(std::vector<double>& xs, double rel_tol, int max_iterations) {
    const bool mine = part_cells > 0;
    const auto set = [&](HYPRE_StructVector v, const std::vector<double>& in) {
      if (mine) // (hypre's argument is not const; it only reads it)
        HYPRE_StructVectorSetBoxValues(v, phlo.data(), phhi.data(), const_cast<double*>(in.data()));
      HYPRE_StructVectorAssemble(v);
    };
    const auto get = [&](HYPRE_StructVector v, std::vector<double>& out) {
      out.resize(static_cast<std::size_t>(part_cells));
      if (mine) HYPRE_StructVectorGetBoxValues(v, phlo.data(), phhi.data(), out.data());
    };
    const int handle = sh.comm;
    SharedPcgOperators op;
    op.apply = [&](const std::vector<double>& in, std::vector<double>& out) {
      set(x, in);
      HYPRE_StructMatrixMatvec(1.0, A, x, 0.0, y);
      get(y, out);
    };
    op.precondition = [&](const std::vector<double>& in, std::vector<double>& out) {
      set(b, in);
      // PFMG's first relaxation assumes a zero guess, yet on a periodic axis of odd period it
      // reads the points of its own colour across the period: they must be zero (the last
      // product's input otherwise, and PCG stagnated on periods of 5).
      HYPRE_StructVectorSetConstantValues(x, 0.0);
      HYPRE_StructPFMGSolve(mg, A, b, x);
      get(x, out);
    };
    op.dot = [&](const std::vector<double>& u, const std::vector<double>& v) {
      return rank_dot(handle, cells, u.data(), v.data(), u.size());
    };
    const SharedPcgResult r = shared_pcg(op, buf_b, xs, rel_tol, max_iterations, work);
    HYPRE_ClearAllErrors();
    LinearSolveStats st;
    st.iterations = r.iterations;
    st.relative_residual = r.relative_residual;
    st.converged = r.converged;
    return st;
  }

  // Shared: the parts of every rank into x (padded layout), the same bits on every rank.
  void gather_into(std::vector<double>& xv) {
    const long sy = padded[0], sz = static_cast<long>(padded[0]) * padded[1];
    if (!sh.whole_solution) {
      std::size_t q = 0;
      for (int k = plo[2]; k <= phi[2]; ++k)
        for (int j = plo[1]; j <= phi[1]; ++j)
          for (int i = plo[0]; i <= phi[0]; ++i, ++q)
            xv[static_cast<std::size_t>(i + j * sy + k * sz)] = buf_x[q];
      return;
    }
    gathered.resize(static_cast<std::size_t>(cells));
    if (sh.comm == -1 || sh.size == 1) {
      std::copy(buf_x.begin(), buf_x.end(), gathered.begin());
    } else {
      MPI_Allgatherv(buf_x.data(), static_cast<int>(part_cells), MPI_DOUBLE, gathered.data(),
                     counts.data(), displs.data(), MPI_DOUBLE, comm());
    }
    std::size_t q = 0;
    for (const auto& pr : parts)
      for (int k = pr[2]; k <= pr[5]; ++k)
        for (int j = pr[1]; j <= pr[4]; ++j)
          for (int i = pr[0]; i <= pr[3]; ++i, ++q)
            xv[static_cast<std::size_t>(i + j * sy + k * sz)] = gathered[q];
  }

  // Shared: the box cut into sh.size parts (sh.parts, or each prime factor of the size, largest
  // first, given to the axis whose parts are longest); rank r has coordinates (x slowest).
  void cut_into_parts() {
    std::array<int, 3> n{}, np = sh.parts;
    for (int d = 0; d < 3; ++d) n[d] = hi[d] - lo[d] + 1;
    if (np[0] * np[1] * np[2] != sh.size) {
      if (np != std::array<int, 3>{0, 0, 0})
        throw std::logic_error("StructLinearSolver::share: parts do not multiply to the size");
      np = {1, 1, 1};
      std::vector<int> primes;
      for (int v = sh.size, f = 2; v > 1;) {
        if (v % f == 0) {
          primes.push_back(f);
          v /= f;
        } else {
          ++f;
        }
      }
      std::sort(primes.rbegin(), primes.rend());
      for (const int f : primes) {
        int best = 0;
        for (int d = 1; d < 3; ++d)
          if (static_cast<long>(n[d]) * np[best] > static_cast<long>(n[best]) * np[d]) best = d;
        np[best] *= f;
      }
    }
    parts.clear();
    counts.clear();
    displs.clear();
    int offset = 0;
    for (int r = 0; r < sh.size; ++r) {
      const std::array<int, 3> c{r / (np[1] * np[2]), (r / np[2]) % np[1], r % np[2]};
      std::array<int, 6> pr{};
      for (int d = 0; d < 3; ++d) {
        pr[d] = lo[d] + static_cast<int>(static_cast<long>(n[d]) * c[d] / np[d]);
        pr[d + 3] = lo[d] + static_cast<int>(static_cast<long>(n[d]) * (c[d] + 1) / np[d]) - 1;
      }
      parts.push_back(pr);
      const long cnt = count({pr[0], pr[1], pr[2]}, {pr[3], pr[4], pr[5]});
      counts.push_back(static_cast<int>(cnt));
      displs.push_back(offset);
      offset += static_cast<int>(cnt);
    }
    const auto& mine = parts[static_cast<std::size_t>(sh.rank)];
    set_part({mine[0], mine[1], mine[2]}, {mine[3], mine[4], mine[5]});
  }

  LinearSolveStats krylov_solve(double rel_tol, int max_iterations) {
    LinearSolveStats st;
    if (symmetric) {
      HYPRE_StructPCGSetTol(krylov, rel_tol);
      HYPRE_StructPCGSetMaxIter(krylov, max_iterations);
      HYPRE_StructPCGSolve(krylov, A, b, x);
      HYPRE_StructPCGGetNumIterations(krylov, &st.iterations);
      HYPRE_StructPCGGetFinalRelativeResidualNorm(krylov, &st.relative_residual);
    } else {
      HYPRE_StructGMRESSetTol(krylov, rel_tol);
      HYPRE_StructGMRESSetMaxIter(krylov, max_iterations);
      HYPRE_StructGMRESSolve(krylov, A, b, x);
      HYPRE_StructGMRESGetNumIterations(krylov, &st.iterations);
      HYPRE_StructGMRESGetFinalRelativeResidualNorm(krylov, &st.relative_residual);
    }
    HYPRE_ClearAllErrors(); // non-convergence is reported in the stats
    st.converged = st.relative_residual <= rel_tol;
    return st;
  }
};

StructLinearSolver::StructLinearSolver(std::array<int, 3> padded, std::array<int, 3> lo,
                                       std::array<int, 3> hi, std::array<bool, 3> periodic,
                                       bool symmetric, const StructSolverOptions& options)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.padded = padded;
  m.lo = lo;
  m.hi = hi;
  m.symmetric = symmetric;
  m.opt = options;
  // hypre's periodic Struct grids misbehave when a period (on any PFMG level) is below 3: the
  // two neighbours along the axis coincide. Periods 1 and 2 are folded into the stencil here;
  // for the others PFMG coarsening is limited so the coarsest period stays >= 3.
  int min_period = 1 << 30;
  for (int d = 0; d < 3; ++d) {
    const int period = hi[d] - lo[d] + 1;
    m.periodic[d] = periodic[d] && period >= 3;
    m.fold[d] = periodic[d] && period < 3 ? period : 0;
    if (m.periodic[d]) min_period = std::min(min_period, period);
  }
  if (min_period < (1 << 30)) {
    m.max_levels = 1;
    for (int p = min_period; p / 2 >= 3; p /= 2) ++m.max_levels;
  }
  // One cell thick along y and not periodic there (2-D runs): the y links are out of the box
  // (0), so hypre gets the 5-point x-z problem.
  if (lo[1] == hi[1] && !periodic[1]) {
    m.ndim = 2;
    m.slot = {0, 1, 2, 5, 6, 0, 0};
    m.nentries = 5;
  }
  const std::array<int, 3> axis = m.axis_of_hypre();
  for (int a = 0; a < m.ndim; ++a)
    m.hperiod[a] = m.periodic[axis[a]] ? hi[axis[a]] - lo[axis[a]] + 1 : 0;
  std::size_t n = 1;
  for (int d = 0; d < 3; ++d) n *= static_cast<std::size_t>(hi[d] - lo[d] + 1);
  m.cells = static_cast<long>(n);
  m.set_part(lo, hi);
  m.band_possible = symmetric && !periodic[0] && !periodic[1] && !periodic[2];
  if (m.band_possible) {
    std::array<int, 3> ext{hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1};
    std::sort(ext.begin(), ext.end());
    const double b = ext[2] > 1   ? static_cast<double>(ext[0]) * ext[1]
                     : ext[1] > 1 ? static_cast<double>(ext[0])
                                  : 0.0;
    m.band_work = 0.5 * static_cast<double>(n) * b * b;
  }
}

StructLinearSolver::~StructLinearSolver() {
  Impl& m = *impl_;
  if (m.krylov) {
    if (m.symmetric)
      HYPRE_StructPCGDestroy(m.krylov);
    else
      HYPRE_StructGMRESDestroy(m.krylov);
  }
  m.destroy_mg();
  if (!m.grid) return; // never solved iteratively: no hypre objects
  HYPRE_StructVectorDestroy(m.x);
  if (m.y) HYPRE_StructVectorDestroy(m.y);
  HYPRE_StructVectorDestroy(m.b);
  HYPRE_StructMatrixDestroy(m.A);
  HYPRE_StructStencilDestroy(m.stencil);
  HYPRE_StructGridDestroy(m.grid);
}

void StructLinearSolver::new_step() {
  impl_->step_started = true;
}

void StructLinearSolver::set_options(const StructSolverOptions& options) {
  impl_->destroy_mg();
  impl_->opt = options;
  impl_->stale = true;
}

const StructSolverOptions& StructLinearSolver::options() const {
  return impl_->opt;
}
long StructLinearSolver::setups() const {
  return impl_->n_setups;
}
long StructLinearSolver::solves() const {
  return impl_->n_solves;
}
long StructLinearSolver::direct_solves() const {
  return impl_->n_direct;
}

LinearSolveStats StructLinearSolver::solve(const StencilSystem& sys, std::vector<double>& x,
                                           double rel_tol, int max_iterations) {
  Impl& m = *impl_;
  if (m.band_possible && m.opt.direct_max_work > 0.0 && m.band_work <= m.opt.direct_max_work) {
    LinearSolveStats st;
    if (m.direct_solve(sys, x, rel_tol, st)) {
      ++m.n_solves;
      ++m.n_direct;
      return st;
    }
    // Not SPD to round-off, or not accurate enough: hypre from here (x: the initial guess).
  }
  if (!m.grid) m.make_hypre();
  const long sx = 1, sy = m.padded[0], sz = static_cast<long>(m.padded[0]) * m.padded[1];
  const std::array<const std::vector<double>*, 7> a{&sys.diag, &sys.xm, &sys.xp, &sys.ym,
                                                    &sys.yp,   &sys.zm, &sys.zp};
  const int ne = m.nentries;
  std::size_t q = 0;
  for (int k = m.plo[2]; k <= m.phi[2]; ++k)
    for (int j = m.plo[1]; j <= m.phi[1]; ++j)
      for (int i = m.plo[0]; i <= m.phi[0]; ++i, ++q) {
        const long p = i * sx + j * sy + k * sz;
        double v[7];
        for (int e = 0; e < 7; ++e) v[e] = (*a[e])[p];
        // Periods 1 and 2: both neighbours are the point itself (1) or the other point (2).
        const int c[3] = {i, j, k};
        for (int d = 0; d < 3; ++d) {
          if (m.fold[d] == 1) {
            v[0] += v[1 + 2 * d] + v[2 + 2 * d];
            v[1 + 2 * d] = v[2 + 2 * d] = 0.0;
          } else if (m.fold[d] == 2) {
            const bool first = c[d] == m.lo[d];
            v[first ? 2 + 2 * d : 1 + 2 * d] += v[first ? 1 + 2 * d : 2 + 2 * d];
            v[first ? 1 + 2 * d : 2 + 2 * d] = 0.0;
          }
          // Links leaving the box along a non-periodic axis are dropped (documented as 0).
          if (!m.periodic[d] && c[d] == m.lo[d]) v[1 + 2 * d] = 0.0;
          if (!m.periodic[d] && c[d] == m.hi[d]) v[2 + 2 * d] = 0.0;
        }
        double* out = &m.values[static_cast<std::size_t>(ne) * q];
        for (int e = 0; e < ne; ++e) out[e] = v[m.slot[e]];
        m.buf_b[q] = sys.rhs[p];
        m.buf_x[q] = x[p];
      }
  const bool mine = m.part_cells > 0;
  int entries[7] = {0, 1, 2, 3, 4, 5, 6};
  if (mine)
    HYPRE_StructMatrixSetBoxValues(m.A, m.phlo.data(), m.phhi.data(), ne, entries, m.values.data());
  HYPRE_StructMatrixAssemble(m.A);
  if (mine) HYPRE_StructVectorSetBoxValues(m.b, m.phlo.data(), m.phhi.data(), m.buf_b.data());
  HYPRE_StructVectorAssemble(m.b);
  if (mine) HYPRE_StructVectorSetBoxValues(m.x, m.phlo.data(), m.phhi.data(), m.buf_x.data());
  HYPRE_StructVectorAssemble(m.x);

  using Reuse = StructSolverOptions::Reuse;
  const bool fresh = !m.mg || m.opt.reuse == Reuse::every_solve ||
                     (m.opt.reuse == Reuse::per_step && m.step_started) ||
                     (m.opt.reuse == Reuse::adaptive && m.stale);
  if (fresh && m.shared) m.set_dxyz(sys);
  if (fresh) m.setup_mg();
  if (m.shared) m.guess = m.buf_x;
  LinearSolveStats st = m.shared ? m.shared_solve(m.guess, rel_tol, max_iterations)
                                 : m.krylov_solve(rel_tol, max_iterations);
  st.setups = fresh ? 1 : 0;
  if (fresh) m.iterations_after_setup = st.iterations;
  if (!st.converged && !fresh) { // the reused set-up was not good enough: redo it and retry
    if (mine) HYPRE_StructVectorSetBoxValues(m.x, m.phlo.data(), m.phhi.data(), m.buf_x.data());
    HYPRE_StructVectorAssemble(m.x);
    if (m.shared) m.set_dxyz(sys);
    m.setup_mg();
    const int before = st.iterations;
    m.guess = m.buf_x;
    st = m.shared ? m.shared_solve(m.guess, rel_tol, max_iterations)
                  : m.krylov_solve(rel_tol, max_iterations);
    m.iterations_after_setup = st.iterations;
    st.iterations += before;
    st.setups = 1;
  }
  m.stale = st.iterations > 2 * m.iterations_after_setup + 2;
  ++m.n_solves;
  if (m.shared) {
    std::swap(m.buf_x, m.guess);
    m.gather_into(x);
    return st;
  }
  HYPRE_StructVectorGetBoxValues(m.x, m.phlo.data(), m.phhi.data(), m.buf_x.data());
  q = 0;
  for (int k = m.lo[2]; k <= m.hi[2]; ++k)
    for (int j = m.lo[1]; j <= m.hi[1]; ++j)
      for (int i = m.lo[0]; i <= m.hi[0]; ++i, ++q) x[i * sx + j * sy + k * sz] = m.buf_x[q];
  return st;
}

void StructLinearSolver::share(const SharedSolve& shared) {
  Impl& m = *impl_;
  if (!m.symmetric) throw std::logic_error("StructLinearSolver::share: symmetric systems only");
  if (m.opt.multigrid != StructSolverOptions::Multigrid::pfmg)
    throw std::logic_error("StructLinearSolver::share: PFMG only (SMG is not checked to be "
                           "independent of the parts)");
  if (m.grid) throw std::logic_error("StructLinearSolver::share: before the first solve only");
  if (shared.size < 1 || shared.rank < 0 || shared.rank >= shared.size)
    throw std::logic_error("StructLinearSolver::share: rank outside 0 .. size - 1");
  if (shared.comm != -1) ensure_mpi_initialised();
  m.shared = true;
  m.sh = shared;
  m.cut_into_parts();
}

bool StructLinearSolver::reads_whole_system() const {
  const Impl& m = *impl_;
  return !m.shared ||
         (m.band_possible && m.opt.direct_max_work > 0.0 && m.band_work <= m.opt.direct_max_work);
}

std::array<int, 3> StructLinearSolver::part_lo() const {
  return impl_->plo;
}
std::array<int, 3> StructLinearSolver::part_hi() const {
  return impl_->phi;
}

} // namespace fluidem::gas
