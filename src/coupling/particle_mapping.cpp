#include "coupling/particle_mapping.hpp"
#include "coupling/interpolation.hpp"

namespace fluidem::coupling {

namespace {
/// The calling thread's cube weights: kept between calls and between flow steps (OpenMP reuses
/// its threads), so that a warm run maps without allocating (the vectors keep their capacity).
CubeWeights& thread_weights() {
  static thread_local CubeWeights w;
  return w;
}
} // namespace

ParticleMapping::ParticleMapping(const gas::GasSolver& gs, const PorositySettings& porosity)
    : gs_(gs), cube_(porosity.method == PorosityMethod::porous_cube), factor_(porosity.cube_factor),
      periodic_(periodic_axes(gs)) {}

void ParticleMapping::velocity_and_pressure_gradient(const Vec3& x, double d, Vec3& u,
                                                     Vec3& grad_p) {
  if (!cube_) {
    velocity_and_pressure_gradient_at(gs_, x, u, grad_p);
    return;
  }
  const gas::GasGrid& g = gs_.grid();
  const std::vector<double>& p = gs_.pressure();
  const double half = 0.5 * factor_ * d;
  CubeWeights& w = thread_weights();
  for (int dir = 0; dir < 3; ++dir) {
    cube_weights(g, dir, x, half, periodic_, w);
    const std::vector<double>& ud = gs_.velocity(dir);
    const auto sd = static_cast<std::size_t>(g.stride[static_cast<std::size_t>(dir)]);
    double uv = 0.0, gv = 0.0;
    for (std::size_t m = 0; m < w.size(); ++m) {
      const auto q = static_cast<std::size_t>(w.q[m]);
      uv += w.w[m] * ud[q];
      gv += w.w[m] * (p[q + sd] - p[q]); // [Deen07 eq. 38] on the face gradients
    }
    u[dir] = uv;
    grad_p[dir] = gv / g.h[static_cast<std::size_t>(dir)];
  }
}

void ParticleMapping::porosity_and_density(const Vec3& x, double d, double& eps, double& rho) {
  if (!cube_) {
    const Stencil s = cell_stencil(gs_.grid(), x, periodic_);
    eps = interpolate(s, gs_.porosity());
    rho = interpolate(s, gs_.density());
    return;
  }
  CubeWeights& w = thread_weights();
  cube_weights(gs_.grid(), cell_component, x, 0.5 * factor_ * d, periodic_, w);
  eps = cube_average(w, gs_.porosity());
  rho = cube_average(w, gs_.density());
}

const CubeWeights& ParticleMapping::face_weights(int dir, const Vec3& x, double d) {
  CubeWeights& w = thread_weights();
  if (cube_) {
    cube_weights(gs_.grid(), dir, x, 0.5 * factor_ * d, periodic_, w); // images already
    return w;
  }
  const Stencil s = face_stencil(gs_.grid(), dir, x);
  w.clear();
  for (int m = 0; m < s.n; ++m) {
    const auto k = static_cast<std::size_t>(m);
    w.q.push_back(periodic_image(gs_.grid(), periodic_, dir, s.q[k]));
    w.w.push_back(s.w[k]);
  }
  return w;
}

} // namespace fluidem::coupling
