#include "coupling/exchange.hpp"
#include "core/error.hpp"
#include "coupling/interpolation.hpp"
#include <cmath>

namespace fluidem::coupling {

namespace {
constexpr double pi = 3.14159265358979323846;
}

void ParticleGasForces::resize(std::size_t n) {
  for (auto* v :
       {&drag_x, &drag_y, &drag_z, &pres_x, &pres_y, &pres_z, &coeff, &ux, &uy, &uz, &eps})
    v->assign(n, 0.0);
}

void validate(const CouplingSettings& c, const gas::GasSettings& gas) {
  if (c.scheme != ExchangeScheme::scheme3)
    throw InputError(std::string("coupling.scheme = ") +
                     (c.scheme == ExchangeScheme::scheme1 ? "1" : "2") +
                     ": not implemented (only scheme 3 [Zhu07 §3.2])");
  if (gas.model != gas::PressureModel::A)
    throw InputError("gas.model = B: the particle force of Model B is not implemented in the "
                     "coupling (use model A)");
  validate(c.porosity);
  if (drag::needs_mean_diameter(c.drag) && !(c.d_mean > 0.0))
    throw InputError(std::string("coupling.d_mean must be > 0 for drag closure '") +
                     std::string(drag::to_string(c.drag)) + "'");
}

void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c) {
  compute_porosity(gs.grid(), p, c.porosity, gs.porosity());
}

void compute_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                             const CouplingSettings& c, ParticleGasForces& out) {
  const std::size_t n = p.size();
  out.resize(n);
  const double mu = gs.settings().viscosity;
  const bool model_a = gs.settings().model == gas::PressureModel::A;
  drag::with_drag_closure(c.drag, [&](auto closure) {
    using C = decltype(closure);
    // Independent per particle: parallel, and the same result for any thread count.
#pragma omp parallel for schedule(static) if (n > 2048)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 x = p.position(i);
      Vec3 u, gp;
      velocity_and_pressure_gradient_at(gs, x, u, gp);
      const Stencil cs = cell_stencil(gs.grid(), x);
      drag::DragInput in;
      in.eps = interpolate(cs, gs.porosity());
      in.rho = interpolate(cs, gs.density());
      in.d = 2.0 * p.radius[i];
      in.mu = mu;
      in.d_mean = c.d_mean;
      const Vec3 v = p.velocity(i);
      const Vec3 slip{u[0] - v[0], u[1] - v[1], u[2] - v[2]};
      in.slip = std::sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]);
      const double vol = pi * in.d * in.d * in.d / 6.0;
      const double ci = vol * C::k(in); // [Deen07 eq. 1]: F = V K (u - v)
      out.coeff[i] = ci;
      out.eps[i] = in.eps;
      out.ux[i] = u[0];
      out.uy[i] = u[1];
      out.uz[i] = u[2];
      out.drag_x[i] = ci * slip[0];
      out.drag_y[i] = ci * slip[1];
      out.drag_z[i] = ci * slip[2];
      if (model_a) { // [Zhu07 eq. 5]: -V grad p on the particle
        out.pres_x[i] = -vol * gp[0];
        out.pres_y[i] = -vol * gp[1];
        out.pres_z[i] = -vol * gp[2];
      }
    }
  });
}

void deposit_momentum_source(gas::GasSolver& gs, const ParticleStore& p,
                             const ParticleGasForces& f) {
  const gas::GasGrid& g = gs.grid();
  const double inv_v = 1.0 / g.cell_volume();
  for (int d = 0; d < 3; ++d) {
    std::vector<double>& K = gs.drag_coefficient(d);
    std::vector<double>& Kus = gs.drag_velocity_term(d);
    std::vector<double>& src = gs.explicit_source(d);
    const std::vector<unsigned char>& role = gs.face_role(d);
    K.assign(g.size(), 0.0);
    Kus.assign(g.size(), 0.0);
    src.assign(g.size(), 0.0);
    const std::vector<double>& v = d == 0 ? p.vx : (d == 1 ? p.vy : p.vz);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const Stencil s = face_stencil(g, d, p.position(i));
      double wsum = 0.0;
      for (int m = 0; m < s.n; ++m) {
        const auto r = role[static_cast<std::size_t>(s.q[static_cast<std::size_t>(m)])];
        if (r == gas::GasSolver::solved || r == gas::GasSolver::pressure_face)
          wsum += s.w[static_cast<std::size_t>(m)];
      }
      if (!(wsum > 0.0)) continue;
      const double ci = f.coeff[i] * inv_v / wsum;
      for (int m = 0; m < s.n; ++m) {
        const auto q = static_cast<std::size_t>(s.q[static_cast<std::size_t>(m)]);
        if (role[q] != gas::GasSolver::solved && role[q] != gas::GasSolver::pressure_face) continue;
        const double w = s.w[static_cast<std::size_t>(m)] * ci;
        K[q] += w;
        Kus[q] += w * v[i];
      }
    }
  }
}

void update_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                            ParticleGasForces& f) {
  const std::size_t n = p.size();
  const bool model_a = gs.settings().model == gas::PressureModel::A;
#pragma omp parallel for schedule(static) if (n > 2048)
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 x = p.position(i);
    Vec3 u, gp;
    velocity_and_pressure_gradient_at(gs, x, u, gp);
    f.ux[i] = u[0];
    f.uy[i] = u[1];
    f.uz[i] = u[2];
    f.drag_x[i] = f.coeff[i] * (u[0] - p.vx[i]);
    f.drag_y[i] = f.coeff[i] * (u[1] - p.vy[i]);
    f.drag_z[i] = f.coeff[i] * (u[2] - p.vz[i]);
    if (model_a) {
      const double d = 2.0 * p.radius[i];
      const double vol = pi * d * d * d / 6.0;
      f.pres_x[i] = -vol * gp[0];
      f.pres_y[i] = -vol * gp[1];
      f.pres_z[i] = -vol * gp[2];
    }
  }
}

void add_forces(ParticleStore& p, const ParticleGasForces& f) {
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.fx[i] += f.drag_x[i] + f.pres_x[i];
    p.fy[i] += f.drag_y[i] + f.pres_y[i];
    p.fz[i] += f.drag_z[i] + f.pres_z[i];
  }
}

} // namespace fluidem::coupling
