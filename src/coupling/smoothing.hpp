// Diffusion-based smoothing of the coupling fields (`coupling.smoothing_length`): the solids
// volume fraction of the cells and the particle -> gas momentum source on the faces are spread
// by solving the diffusion equation
//     d phi / d tau = D lap phi       in pseudo-time tau, from tau = 0 to T,
// as in CFDEM's "smoothing" models (Pirker et al. 2011) and MFiX's diffusion filter (Sun & Xiao
// 2015, Int. J. Multiphase Flow 72). On an infinite domain the solution at T is the convolution
// with the Gaussian of variance 2 D T per axis; fluidem's length sigma is that Gaussian's
// STANDARD DEVIATION: D T = sigma^2 / 2 (Sun & Xiao's bandwidth b = sqrt(4 D T) = sqrt(2) sigma,
// their kernel exp(-|x|^2/b^2); docs/smoothing.md).
//
// Scheme: `steps` backward-Euler steps of dtau = T/steps, each the linear system
//     (I + dtau D L) phi^{m+1} = phi^m,   (L phi)_a = sum_links (phi_a - phi_b) / h_e^2,
// solved by conjugate gradients (the matrix is symmetric positive definite) to a relative
// residual of 1e-14, then phi^{m+1} is RE-EVALUATED in flux form, phi^{m+1}_a = phi^m_a -
// sum_links dtau D (phi*_a - phi*_b)/h_e^2 with the CG solution phi*: every link's flux is
// added to one node and taken from the other, so sum phi^{m+1} = sum phi^m to round-off
// whatever the solver's residual (and phi^{m+1} differs from phi* by the residual only).
// Variance: for the discrete Laplacian on an infinite grid, sum_i (i h)^2 (L phi)_i =
// -2 sum_i phi_i, so each backward-Euler step adds exactly 2 D dtau to the variance per axis:
// after k steps the variance is 2 D T = sigma^2 exactly, for any k (docs/smoothing.md).
//
// The nodes that diffuse ("active"): the interior cells (cells), the SOLVED faces of component d
// (faces: GasSolver::solved; boundary faces, whose values are the inflow/pressure faces' own
// half cells, and ghost faces keep their values). A link joins two active neighbours along an
// axis (zero flux at walls and into ghosts); along a periodic axis the last index (n) is linked
// to the first (1), as the gas solver's images (ghost 0 = cell n; face 0 = face n).
// Serial (one thread): the result does not depend on the thread count.
#pragma once
#include "gas/gas_grid.hpp"
#include "gas/gas_solver.hpp"
#include <array>
#include <cstddef>
#include <utility>
#include <vector>

namespace fluidem::coupling {

/// Backward-Euler pseudo-time steps per smoothing (docs/smoothing.md: one step has the right
/// variance but a kernel ~ exp(-sqrt(2) |x| / sigma); four are close to the Gaussian).
inline constexpr int smoothing_steps = 4;

/// The active nodes of one field and their links, built once per layout.
struct DiffusionDomain {
  std::vector<long> node;             ///< padded-grid index of each active node
  std::vector<int> link_a, link_b;    ///< the two nodes (compact indices) of each link
  std::vector<unsigned char> link_ax; ///< each link's axis
  std::size_t size() const { return node.size(); }
};

/// Interior cells of g.
DiffusionDomain cell_domain(const gas::GasGrid& g, const std::array<bool, 3>& periodic);
/// Faces of component d whose role (GasSolver::face_role(d)) is `solved_role`.
DiffusionDomain face_domain(const gas::GasGrid& g, const std::array<bool, 3>& periodic,
                            const std::vector<unsigned char>& role, unsigned char solved_role);

/// Work space of diffuse (kept by the caller: no allocation once warmed up).
struct DiffusionScratch {
  std::vector<double> x, b, r, p, ap;
};

/// Smooths a (padded layout) over the domain's nodes: `steps` backward-Euler steps of the
/// diffusion equation to D T = sigma^2 / 2 (h: the grid's cell sizes). Other entries of `a` are
/// not touched. Throws InstabilityError if CG does not converge (not expected: the matrix is
/// well conditioned, cond <= 1 + 4 D dtau sum_e 1/h_e^2).
void diffuse(const DiffusionDomain& dom, const std::array<double, 3>& h, double sigma, int steps,
             std::vector<double>& a, DiffusionScratch& s);

/// The smoothing of a coupled run: the layouts of the solver's grid and face roles, and the
/// work space. `configure` once; then `smooth_solid_fraction` after the porosity,
/// `smooth_source` after the momentum source.
class CouplingSmoother {
public:
  /// InputError if sigma is negative, nan or infinite (0: off).
  void configure(const gas::GasGrid& g, const std::array<bool, 3>& periodic,
                 const std::array<const std::vector<unsigned char>*, 3>& face_role,
                 unsigned char solved_role, double sigma);
  /// The same from a gas solver: its grid, periodic axes and face roles (GasSolver::solved).
  /// smooth_velocity = false: with_smoothed_velocity leaves the velocity alone (no source goes
  /// to the gas, coupling.mode one_way / frozen: there is no third law to keep).
  void configure(const gas::GasSolver& gs, double sigma, bool smooth_velocity = true);
  bool enabled() const { return sigma_ > 0.0; }
  /// eps (padded, interior cells): the solid fraction 1 - eps smoothed, then eps = 1 - s,
  /// capped at 1 (a solid fraction below 0 by the solver's residual); periodic ghosts refilled.
  /// Throws InstabilityError if a cell ends below `min_eps` (not expected: the smoothing of a
  /// field is a weighted mean of it, its maximum does not rise).
  void smooth_porosity(std::vector<double>& eps, double min_eps);
  /// One face array of component d (K, K_us or f of the gas solver).
  void smooth_faces(int d, std::vector<double>& a);
  /// The particle -> gas source of the solver, every component: drag_coefficient(d),
  /// drag_velocity_term(d) and explicit_source(d) each smoothed with the same operator.
  void smooth_momentum_source(gas::GasSolver& gs);

  /// Calls f() with the solver's gas velocity replaced by the smoothed one (the same operator
  /// on the solved faces, periodic ghosts refilled), then puts the solver's back (also if f
  /// throws). The particles reading the gas velocity inside f (compute_particle_forces,
  /// update_particle_forces) then see the ADJOINT of the smoothing of the source: with G
  /// symmetric, sum_f (G K)_f u_f = sum_f K_f (G u)_f, so the gas receives exactly minus the
  /// particles' drag (Newton's third law to round-off; docs/smoothing.md). Off: just f().
  template <class F>
  void with_smoothed_velocity(gas::GasSolver& gs, F&& f) {
    if (!enabled() || !smooth_velocity_) {
      f();
      return;
    }
    for (int d = 0; d < 3; ++d) {
      std::vector<double>& v = velocity_[static_cast<std::size_t>(d)];
      v = gs.velocity(d); // (no allocation once warmed up)
      smooth_faces(d, v);
      gas::fill_periodic_ghosts(g_, periodic_, v);
      std::swap(gs.velocity(d), v);
    }
    struct Restore {
      gas::GasSolver& gs;
      std::array<std::vector<double>, 3>& v;
      ~Restore() {
        for (int d = 0; d < 3; ++d) std::swap(gs.velocity(d), v[static_cast<std::size_t>(d)]);
      }
    } restore{gs, velocity_};
    f();
  }

private:
  std::array<std::vector<double>, 3> velocity_; ///< the smoothed gas velocity (work space)
  gas::GasGrid g_;
  std::array<bool, 3> periodic_{};
  double sigma_ = 0.0;
  bool smooth_velocity_ = true;
  DiffusionDomain cells_;
  std::array<DiffusionDomain, 3> faces_;
  std::vector<double> solid_;
  DiffusionScratch scratch_;
};

} // namespace fluidem::coupling
