// Volume-averaged Navier-Stokes solver for the gas phase [Deen07 eq. 7-9], Model A or B
// [Zhu07 eq. 4-7], ideal gas [Hoomans96 eq. 42-44] or incompressible, on the staggered grid of
// gas_grid.hpp. Backward Euler in time, first-order upwind convection, SIMPLEC pressure-
// correction iterations per flow step, semi-implicit particle drag (docs/gas.md).
//
// Coupling interface (all arrays in the padded layout of GasGrid, face arrays per component
// d = 0, 1, 2 = x, y, z, value at idx(i, j, k) = high face of cell (i, j, k)):
//  - porosity(): new-time gas volume fraction at cell centres, set by the caller before step();
//    the solver keeps the previous step's field for d(eps rho)/dt.
//  - drag_coefficient(d) K >= 0 [kg m^-3 s^-1], drag_velocity_term(d) K_us = K u_s
//    [kg m^-2 s^-2 = N m^-3], explicit_source(d) f [N m^-3]: the particle momentum source ON
//    THE GAS per unit volume, S = K_us - K u_new + f (positive along +axis), set per step.
//    On the solved faces it enters the momentum equations; on an inflow face (velocity
//    prescribed) it is the force on the gas of the half cell between the face and the first
//    cell centre, and sets the pressure on the face (inflow_face_pressure()).
//  - applied_source(d): S actually applied with the converged u_new, per face, N m^-3.
// The gas module knows nothing about particles.
#pragma once
#include "core/gas_settings.hpp"
#include "core/vec3.hpp"
#include "gas/gas_boundary.hpp"
#include "gas/gas_grid.hpp"
#include "gas/gauss_seidel.hpp"
#include "gas/plane_slabs.hpp"
#include "gas/pressure_solver.hpp"
#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fluidem::gas {

/// How the linear systems of a flow step are solved (docs/gas.md, "Linear solvers"). The
/// defaults are the measured choice; the alternatives are kept for bench/gas_bench.cpp.
struct LinearSolverOptions {
  /// Momentum: red-black Gauss-Seidel (falling back to hypre GMRES + PFMG when it would need
  /// more than momentum_max_sweeps sweeps), or hypre GMRES + PFMG always.
  enum class Momentum { gauss_seidel, hypre };
  Momentum momentum = Momentum::gauss_seidel;
  int momentum_max_sweeps = 50;
  /// Pressure correction: banded Cholesky on small grids (up to direct_max_work), else hypre
  /// PCG with this preconditioner and set-up reuse.
  StructSolverOptions pressure = default_pressure_options();

  /// The defaults with the direct solver on for factorisations of up to 2e6 multiply-adds
  /// (e.g. 1500 cells with a band of 50; the Tsuji grid 15 x 25 needs 4.2e4): measured
  /// faster than hypre PCG + PFMG there (bench/gas_bench.cpp).
  static StructSolverOptions default_pressure_options() {
    StructSolverOptions o;
    o.direct_max_work = 2e6;
    return o;
  }
};

/// Work done by the linear solvers since construction (for benchmarks and diagnostics).
struct LinearSolverCounters {
  long momentum_solves = 0, momentum_sweeps = 0;     ///< Gauss-Seidel solves and sweeps
  long momentum_fallbacks = 0;                       ///< solves handed to hypre GMRES
  long pressure_solves = 0, pressure_iterations = 0; ///< hypre PCG solves and iterations
  long pressure_setups = 0;                          ///< multigrid set-ups of the pressure solver
  double pressure_seconds = 0.0;                     ///< wall time in the pressure solves
};

class GasSolver {
public:
  /// Validates the settings (InputError naming the key) and sets the initial state:
  /// porosity 1, pressure initial_pressure, velocity initial_velocity on non-boundary faces.
  explicit GasSolver(const GasSettings& settings);
  ~GasSolver();
  GasSolver(const GasSolver&) = delete;
  GasSolver& operator=(const GasSolver&) = delete;

  const GasSettings& settings() const { return s_; }
  const GasGrid& grid() const { return g_; }
  const BoundaryMap& boundary() const { return bc_; }

  /// Gas volume fraction at cell centres (interior cells; ghosts are set by the solver).
  std::vector<double>& porosity() { return eps_; }
  const std::vector<double>& porosity() const { return eps_; }
  const std::vector<double>& porosity_old() const { return eps_old_; }
  /// Makes the old porosity equal to the current one (after setting the initial field).
  void sync_old_porosity();

  std::vector<double>& drag_coefficient(int d) { return K_[d]; }
  std::vector<double>& drag_velocity_term(int d) { return Kus_[d]; }
  std::vector<double>& explicit_source(int d) { return f_[d]; }
  const std::vector<double>& explicit_source(int d) const { return f_[d]; }
  /// K_us - K u + f on every face with the current u, N m^-3 (0 on faces that take no source:
  /// those neither solved nor inflow faces).
  std::vector<double> applied_source(int d) const;

  /// Interstitial gas velocity component d on its faces, m/s.
  const std::vector<double>& velocity(int d) const { return u_[d]; }
  std::vector<double>& velocity(int d) { return u_[d]; }
  /// Pressure at cell centres (ghosts included), Pa. Mutable for initial conditions.
  const std::vector<double>& pressure() const { return p_; }
  std::vector<double>& pressure() { return p_; }
  /// Gas density at cell centres, kg/m^3 (recomputed from p in step()).
  const std::vector<double>& density() const { return rho_; }

  /// Advances from `time` to `time + dt` (inflow velocities taken at time + dt). Throws
  /// InstabilityError when the pressure-correction iterations do not converge or give NaN.
  void step(double time, double dt);

  /// Trilinear interpolation of the cell-centre pressure (ghost values at the boundary), Pa.
  double pressure_at(const Vec3& x) const;

  /// The pressure on the inflow face whose momentum-grid index is q (component d), Pa: the
  /// momentum balance of the gas in the half cell between the face and the first cell centre
  /// (docs/gas.md, "Pressure on an inflow face"). After each step() (and at construction) the
  /// inflow ghost cell holds 2 p_b - p_1, so that the face value is the mean of the ghost and
  /// the first cell, as on a pressure face, and interpolation reads p_b on the face.
  double inflow_face_pressure(int d, long q) const;

  /// What carries over from one flow step to the next (for checkpoints): velocities, pressure,
  /// porosity (new and old), density and the last step's diagnostics.
  struct State {
    std::array<std::vector<double>, 3> u;
    std::vector<double> p, eps, eps_old, rho;
    std::int64_t last_iterations = 0;
    double last_mass_residual = 0.0, last_velocity_change = 0.0, boundary_outflow = 0.0;
  };
  State state() const;
  /// Restores a state() of a solver with the same settings (InputError if the sizes differ).
  void restore(const State& s);
  /// Drops what the linear solvers keep between solves (the reused multigrid set-ups), so that
  /// the next flow step is solved as by a freshly made solver: a checkpoint is such a point in
  /// the run that writes it, so that a run restarted from it repeats the same solves bitwise.
  void reset_solver_history();

  /// InstabilityError naming the face and time if |u| dt / h exceeds gas.solver.max_courant on
  /// a face (called by the coupled run after each flow step; the solver itself, backward Euler
  /// with upwinding, is stable at any Courant number, and its tests take large steps to steady
  /// states).
  void check_courant(double t_new, double dt) const;

  int last_iterations() const { return last_iterations_; }
  /// sum over cells |mass imbalance of the step| / gas mass in the domain (dimensionless).
  double last_mass_residual() const { return last_mass_residual_; }
  /// Largest velocity change in the last pressure-correction iteration, m/s.
  double last_velocity_change() const { return last_velocity_change_; }
  /// Gas mass in the domain, sum eps rho V over interior cells, kg.
  double gas_mass() const;
  /// Net mass flow out through the domain boundary in the last step (the fluxes of the
  /// discrete continuity equation), kg/s.
  double boundary_outflow() const { return boundary_outflow_; }

  /// OpenMP threads (docs/gas.md, "Threads"): the momentum and pressure-correction assembly
  /// loops run threaded on grids of at least `assembly` interior cells, the Gauss-Seidel sweeps
  /// from `gauss_seidel` cells on. Every threaded loop writes per cell or face (no reductions
  /// across threads): results do not depend on the thread count nor on these thresholds. The
  /// defaults are above the grids measured (up to 40^3): on the 2-core machines threads did
  /// not pay there (hypre, serial, is more than half of the step).
  static constexpr long default_parallel_cells = 1L << 17;
  static constexpr long default_gauss_seidel_parallel_cells = 1L << 20;
  void set_parallel_cells(long assembly, long gauss_seidel = default_gauss_seidel_parallel_cells);
  bool threaded_assembly() const { return parallel_; }

  const LinearSolverOptions& linear_solver_options() const { return lin_; }
  /// Changes the linear solvers (results stay within the linear tolerance).
  void set_linear_solver_options(const LinearSolverOptions& options);
  /// Steps the gas together with the ranks of `ranks`, with the same bits for any number of
  /// them (docs/parallel.md, "The gas on several ranks"); before the first step only,
  /// collective from then on. The pressure correction is solved in parts (StructLinearSolver::
  /// share) and the momentum equations by planes (RedBlackGaussSeidel::share). When the pressure
  /// solve is shared by parts (not the direct solver) and the outflow is not rescaled
  /// (balance_outflow), each rank also does the rest of the step on its own z planes
  /// (PlaneSlabs; with more ranks than planes some have none) with halo planes, and the fields are
  /// gathered once at the end of the step; otherwise the rest is repeated on every rank. Either way
  /// the sums of the convergence test are taken per plane and then over the planes in order.
  void share(const SharedSolve& ranks);
  /// Whether each rank steps only its own z planes (share()).
  bool distributed() const { return dist_; }
  const LinearSolverCounters& linear_counters() const { return counters_; }

  /// Face roles (internal, exposed for tests and coupling): solved, fixed, ...
  /// inflow: the normal face of an inflow patch, velocity prescribed like a fixed face; it
  /// takes the particles' momentum source of its half cell (inflow_face_pressure).
  enum FaceRole : unsigned char {
    none = 0,
    solved,
    fixed,
    outflow,
    pressure_face,
    periodic_copy,
    inflow
  };
  const std::vector<unsigned char>& face_role(int d) const { return role_[d]; }

private:
  // gas_solver.cpp
  void init_roles();
  void build_boundary_lists();
  void apply_scalar_bcs();
  /// Inflow ghost pressures 2 p_b - p_1 from inflow_face_pressure (after apply_scalar_bcs and
  /// update_density: the ghost's density stays that of the first cell's pressure).
  void set_inflow_ghost_pressures();
  void apply_velocity_bcs(double t_new, bool set_inflow);
  void fill_periodic(std::vector<double>& a) const;
  /// Distributed (dist_): the periodic x and y images, then the halo planes (z's images
  /// across the period among them); otherwise fill_periodic.
  void fill_periodic_and_halo(std::vector<double>& a) const;
  /// The range of z planes of component d's faces (or cells, d = -1) this rank computes:
  /// its own planes within the box of rows with a role (faces c[d] = 0..n_d, others 1..n).
  std::array<int, 2> own_planes(int d) const;
  /// The padded indices [first, last) of the planes current on this rank between exchanges:
  /// its own planes and the halo planes beside them (distributed), or the whole grid.
  std::array<long, 2> current_range() const;
  /// The momentum Gauss-Seidel solver of component d shared as share() decided.
  void share_momentum_gs(int d);
  void update_density();
  double rho_of_p(double p) const;
  // gas_equations.cpp
  void compute_mass_fluxes();
  void balance_outflow(double dt);
  void solve_momentum(int d, double dt);
  /// Lower corner of the box of momentum unknowns of component d (upper: n).
  std::array<int, 3> momentum_box_lo(int d) const;
  void solve_pressure_correction(double dt);
  /// Adds plane k's cells' |mass imbalance| (kg/s) and gas mass (kg) to the sums, in i, j order.
  void add_plane_sums(int k, double dt, double& sum_abs, double& mass) const;
  double mass_residual(double dt, double& out_rate);
  /// shared_: the sums by z plane, then over the planes (the same bits on any ranks).
  double plane_mass_residual(double dt, double& out_rate);
  /// InstabilityError: a linear solve did not reach gas.solver.linear_tolerance.
  [[noreturn]] void throw_linear_failure(const std::string& what, const LinearSolveStats& st) const;

  GasSettings s_;
  GasGrid g_;
  BoundaryMap bc_;
  bool compressible_ = true;
  double psi_ = 0.0; ///< d rho / d p, s^2/m^2 (ideal gas M/(R T); 0 incompressible)

  std::vector<double> eps_, eps_old_, p_, rho_, rho_old_, pc_;
  std::array<std::vector<double>, 3> u_, u_old_, u_iter_, K_, Kus_, f_, F_, dcoef_;
  std::array<std::vector<unsigned char>, 3> role_;
  // Boundary work lists, built once in the order of the original grid sweeps (later entries
  // may read values written by earlier ones at edges and corners).
  struct ScalarGhost { ///< ghost cell q next to interior (or ghost) cell `in`
    long q, in;
    const BoundaryPatch* patch;
  };
  struct FaceCopy { ///< u[dst] = factor * u[src]
    long dst, src;
    double factor;
  };
  struct FixedFace { ///< normal velocity on a wall (0) or inflow face
    long q;
    const BoundaryPatch* inflow; ///< nullptr: wall
    double sign;                 ///< +1 on a low face (into the domain along +axis), -1 high
  };
  struct DomainFace { ///< a face on the domain boundary, for the net outflow
    int d;
    long q;
    double sign; ///< -1 low face, +1 high face
  };
  std::vector<ScalarGhost> scalar_ghosts_;
  /// Indexes into scalar_ghosts_ of the edge and corner ghosts beside inflow ghosts.
  std::vector<std::size_t> inflow_layer_ghosts_;
  std::array<std::vector<FaceCopy>, 3> outflow_copies_, tangential_ghosts_;
  std::array<std::vector<FixedFace>, 3> fixed_faces_;
  std::vector<FaceCopy> pc_ghosts_; ///< pressure-correction ghosts: -1 (pressure) or 1 * interior
  std::vector<DomainFace> domain_faces_;
  StencilSystem sys_;
  LinearSolverOptions lin_;
  LinearSolverCounters counters_;
  std::array<std::unique_ptr<RedBlackGaussSeidel>, 3> momentum_gs_;
  SharedSolve momentum_ranks_;     ///< comm kThisProcessAlone: the momentum solves are not shared
  bool shared_ = false;            ///< share() called: the rank-independent sums
  bool dist_ = false;              ///< each rank steps its own z planes (share())
  PlaneSlabs slabs_;               ///< the planes of this rank (all of them unless dist_)
  std::vector<double> plane_sums_; ///< per plane: |mass imbalance|, mass, outflow
  std::array<std::unique_ptr<StructLinearSolver>, 3> momentum_solver_; ///< made when needed
  std::unique_ptr<StructLinearSolver> pressure_solver_;
  double step_time_ = 0.0; ///< start of the step being taken (for messages)
  bool parallel_ = false;

  int last_iterations_ = 0;
  double last_mass_residual_ = 0.0;
  double last_velocity_change_ = 0.0;
  double boundary_outflow_ = 0.0;
};

} // namespace fluidem::gas
