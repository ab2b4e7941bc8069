// The kernel that maps gas quantities to a particle and the particle's force back to the gas
// [Deen07 §3.5], chosen with the porosity method (coupling.porosity):
//  - "cell": the trilinear stencils of the 4/8 nearest nodes [Hoomans96 eq. 40-41]
//    (interpolation.hpp);
//  - "porous_cube": the particle's porous cube of side a d [Deen07 eq. 38-39]
//    (cube_mapping.hpp), the same cube that gives the porosity [Deen07 eq. 37]. The gas state a
//    particle sees is the cube average of the control volumes it overlaps, and its force goes
//    back with the same weights, so the exchange conserves momentum as with the stencils.
// Both resolve periodic images (interpolation.hpp). The cube weights are scratch space of the
// calling thread, kept between calls (no allocation once warm).
#pragma once
#include "core/coupling_settings.hpp"
#include "core/vec3.hpp"
#include "coupling/cube_mapping.hpp"
#include "gas/gas_solver.hpp"
#include <array>

namespace fluidem::coupling {

class ParticleMapping {
public:
  ParticleMapping(const gas::GasSolver& gs, const PorositySettings& porosity);

  /// True if the porous cube is the kernel.
  bool cube() const { return cube_; }
  /// Interstitial gas velocity (m/s) and pressure gradient (Pa/m) at a particle of diameter d at
  /// x: per component d, the values on its faces and the face gradients (p_+ - p_-)/h_d.
  void velocity_and_pressure_gradient(const Vec3& x, double d, Vec3& u, Vec3& grad_p);
  /// Porosity and gas density at the particle (cell-centre control volumes).
  void porosity_and_density(const Vec3& x, double d, double& eps, double& rho);
  /// Both of the above together (the porous cube's lists computed once).
  void gas_at(const Vec3& x, double d, Vec3& u, Vec3& grad_p, double& eps, double& rho);
  /// Porous cube only: the lists of the weights of component `dir` (for_cube_weights) for a
  /// particle of diameter d at x, periodic images resolved (for the deposit of forces). Valid
  /// until the calling thread's next call of any ParticleMapping.
  const CubeAxes& cube_axes_of(int dir, const Vec3& x, double d);

private:
  const gas::GasSolver& gs_;
  bool cube_ = false;
  double factor_ = 0.0; ///< cube side / particle diameter, a [Deen07 eq. 34]
  std::array<bool, 3> periodic_{};
};

} // namespace fluidem::coupling
