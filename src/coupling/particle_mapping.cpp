#include "coupling/particle_mapping.hpp"
#include "coupling/interpolation.hpp"

namespace fluidem::coupling {

namespace {
/// The calling thread's cube lists: kept between calls and between flow steps (OpenMP reuses
/// its threads), so that a warm run maps without allocating (the vectors keep their capacity).
CubeAxes& thread_axes() {
  static thread_local CubeAxes a;
  return a;
}

/// u and grad p from a cube's lists (all six): per component d, sum w u_d and the face gradients
/// (p_+ - p_-)/h_d [Deen07 eq. 38].
void cube_velocity_and_gradient(const gas::GasSolver& gs, const CubeAxes& a, Vec3& u,
                                Vec3& grad_p) {
  const gas::GasGrid& g = gs.grid();
  const double* p = gs.pressure().data();
  for (int dir = 0; dir < 3; ++dir) {
    const double* ud = gs.velocity(dir).data();
    const long sd = g.stride[static_cast<std::size_t>(dir)];
    double uv = 0.0, gv = 0.0;
    for_cube_weights(g, a, dir, [&](long q, double w) {
      uv += w * ud[q];
      gv += w * (p[q + sd] - p[q]);
    });
    u[dir] = uv;
    grad_p[dir] = gv / g.h[static_cast<std::size_t>(dir)];
  }
}

/// eps and rho from a cube's cell lists.
void cube_porosity_and_density(const gas::GasSolver& gs, const CubeAxes& a, double& eps,
                               double& rho) {
  const double* e = gs.porosity().data();
  const double* r = gs.density().data();
  eps = 0.0;
  rho = 0.0;
  for_cube_weights(gs.grid(), a, cell_component, [&](long q, double w) { eps += w * e[q]; });
  for_cube_weights(gs.grid(), a, cell_component, [&](long q, double w) { rho += w * r[q]; });
}
} // namespace

ParticleMapping::ParticleMapping(const gas::GasSolver& gs, const PorositySettings& porosity)
    : gs_(gs), cube_(porosity.method == PorosityMethod::porous_cube), factor_(porosity.cube_factor),
      periodic_(periodic_axes(gs)) {}

void ParticleMapping::velocity_and_pressure_gradient(const Vec3& x, double d, Vec3& u,
                                                     Vec3& grad_p) {
  if (!cube_) {
    u = gas_velocity_at(gs_, x); // (the coupling's loops use the compact stencils instead)
    grad_p = pressure_gradient_at(gs_, x);
    return;
  }
  CubeAxes& a = thread_axes();
  cube_axes(gs_.grid(), x, 0.5 * factor_ * d, periodic_, a);
  cube_velocity_and_gradient(gs_, a, u, grad_p);
}

void ParticleMapping::porosity_and_density(const Vec3& x, double d, double& eps, double& rho) {
  if (!cube_) {
    const Stencil s = cell_stencil(gs_.grid(), x, periodic_);
    eps = interpolate(s, gs_.porosity());
    rho = interpolate(s, gs_.density());
    return;
  }
  CubeAxes& a = thread_axes();
  cube_axes(gs_.grid(), cell_component, x, 0.5 * factor_ * d, periodic_, a);
  cube_porosity_and_density(gs_, a, eps, rho);
}

void ParticleMapping::gas_at(const Vec3& x, double d, Vec3& u, Vec3& grad_p, double& eps,
                             double& rho) {
  if (!cube_) {
    velocity_and_pressure_gradient(x, d, u, grad_p);
    porosity_and_density(x, d, eps, rho);
    return;
  }
  CubeAxes& a = thread_axes();
  cube_axes(gs_.grid(), x, 0.5 * factor_ * d, periodic_, a);
  cube_velocity_and_gradient(gs_, a, u, grad_p);
  cube_porosity_and_density(gs_, a, eps, rho);
}

const CubeAxes& ParticleMapping::cube_axes_of(int dir, const Vec3& x, double d) {
  CubeAxes& a = thread_axes();
  cube_axes(gs_.grid(), dir, x, 0.5 * factor_ * d, periodic_, a); // images already
  return a;
}

} // namespace fluidem::coupling
