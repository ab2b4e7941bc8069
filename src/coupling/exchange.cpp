#include "coupling/exchange.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"
#include "coupling/interpolation.hpp"
#include "coupling/particle_mapping.hpp"
#include "coupling/trilinear.hpp"
#include <cmath>
#include <limits>

namespace fluidem::coupling {

namespace {
constexpr double pi = 3.14159265358979323846;
}

std::array<std::vector<double>*, 11> ParticleGasForces::per_particle() {
  return {&drag_x, &drag_y, &drag_z, &pres_x, &pres_y, &pres_z, &coeff, &ux, &uy, &uz, &eps};
}

void ParticleGasForces::resize(std::size_t n) {
  for (auto* v : per_particle()) v->assign(n, 0.0);
}

namespace {

/// The larger of a and b, NaN if either is (a bound of the fixed-point sums, rank_sum.hpp).
double nan_or_max(double a, double b) {
  return std::isnan(a) || std::isnan(b) ? std::numeric_limits<double>::quiet_NaN() : std::max(a, b);
}

/// u_c: mean of the two faces of cell q (grid index) along d (the face at q is the HIGH one).
double cell_gas_velocity(const gas::GasSolver& gs, long q, int d) {
  const std::vector<double>& u = gs.velocity(d);
  const long s = gs.grid().stride[static_cast<std::size_t>(d)];
  return 0.5 * (u[static_cast<std::size_t>(q - s)] + u[static_cast<std::size_t>(q)]);
}

/// u and grad p at a particle from its face stencils st[0..2] (NY = 1: 2-D, where component 1 is
/// 0; NY = 2: 3-D) and the face pressure differences dp of face_pressure_differences: the values
/// of gas_velocity_at and pressure_gradient_at (interpolation.hpp).
template <int NY>
[[gnu::always_inline]] inline void
velocity_and_gradient(const gas::GasSolver& gs, const std::array<std::vector<double>, 3>& dp,
                      const TrilinearStencil* st, Vec3& u, Vec3& grad_p) {
  const gas::GasGrid& g = gs.grid();
  for (int d = 0; d < 3; ++d) {
    if (NY == 1 && d == 1) {
      u[1] = 0.0;
      grad_p[1] = 0.0;
      continue;
    }
    const auto k = static_cast<std::size_t>(d);
    double uv = 0.0, gv = 0.0;
    trilinear_sums<NY>(st[d], g.stride[1], g.stride[2], gs.velocity(d).data(), dp[k].data(), uv,
                       gv);
    u[d] = uv;
    grad_p[d] = gv / g.h[k];
  }
}

/// Cell averages of schemes 1 and 2 (exchange.hpp): out.cell, cell_coeff, cell_v*; for
/// scheme 2 also overwrites the per-particle drag, coeff, u, eps with the shares of F_c.
template <class Closure>
void compute_cell_forces(const gas::GasSolver& gs, const ParticleStore& p,
                         const CouplingSettings& c, ParticleGasForces& out, const RankSum* ranks) {
  const gas::GasGrid& g = gs.grid();
  const std::size_t n = p.size(), nc = g.size();
  out.cell.assign(n, 0);
  out.cell_coeff.assign(nc, 0.0);
  out.cell_vx.assign(nc, 0.0);
  out.cell_vy.assign(nc, 0.0);
  out.cell_vz.assign(nc, 0.0);
  std::vector<double>& vs = out.cell_solid;
  std::vector<double>& mass = out.cell_mass;
  std::vector<double>& sd2 = out.cell_d2;
  std::vector<double>& sd3 = out.cell_d3;
  for (std::vector<double>* a : {&vs, &mass, &sd2, &sd3}) a->assign(nc, 0.0);
  // The sums over the particles of each cell: solid volume, d^2, d^3, mass, momentum.
  std::array<std::vector<double>*, 7> sums{&vs,          &sd2,         &sd3,        &mass,
                                           &out.cell_vx, &out.cell_vy, &out.cell_vz};
  const auto parts_of = [&](std::size_t i) {
    const double d = 2.0 * p.radius[i], m = p.mass[i];
    return std::array<double, 7>{pi * d * d * d / 6.0, d * d,       d * d * d,  m,
                                 m * p.vx[i],          m * p.vy[i], m * p.vz[i]};
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto cc = g.cell_of(p.position(i));
    out.cell[i] = g.idx(cc[0], cc[1], cc[2]);
  }
  if (ranks) { // fixed point over the ranks (rank_sum.hpp): the largest part of each sum
    std::array<double, 7> largest{};
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<double, 7> v = parts_of(i);
      for (std::size_t f = 0; f < 7; ++f) largest[f] = nan_or_max(largest[f], std::abs(v[f]));
    }
    out.fixed.start(nc, largest, static_cast<std::int64_t>(n), *ranks);
    for (std::size_t i = 0; i < n; ++i) {
      const std::array<double, 7> v = parts_of(i);
      for (std::size_t f = 0; f < 7; ++f)
        out.fixed.add(f, static_cast<std::size_t>(out.cell[i]), v[f]);
    }
    out.fixed.reduce(*ranks);
    for (std::size_t f = 0; f < 7; ++f) out.fixed.result(f, *sums[f]);
  } else {
    for (std::size_t i = 0; i < n; ++i) {
      const auto uq = static_cast<std::size_t>(out.cell[i]);
      const std::array<double, 7> v = parts_of(i);
      for (std::size_t f = 0; f < 7; ++f) (*sums[f])[uq] += v[f];
    }
  }
  const double mu = gs.settings().viscosity;
  const bool divide_by_eps = particle_force_form(c, gs.settings()) == ParticleForceForm::buoyancy;
  for (std::size_t q = 0; q < nc; ++q) {
    if (!(vs[q] > 0.0)) continue;
    if (mass[q] > 0.0) {
      out.cell_vx[q] /= mass[q];
      out.cell_vy[q] /= mass[q];
      out.cell_vz[q] /= mass[q];
    }
    const long lq = static_cast<long>(q);
    const double slip[3] = {cell_gas_velocity(gs, lq, 0) - out.cell_vx[q],
                            cell_gas_velocity(gs, lq, 1) - out.cell_vy[q],
                            cell_gas_velocity(gs, lq, 2) - out.cell_vz[q]};
    drag::DragInput in;
    in.eps = gs.porosity()[q];
    in.rho = gs.density()[q];
    // Sauter mean of the cell's particles (of their real particles: coarse graining)
    in.d = sd3[q] / sd2[q] * c.drag_diameter_factor;
    in.mu = mu;
    in.d_mean = c.d_mean;
    in.slip = std::sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]);
    out.cell_coeff[q] = vs[q] * Closure::k(in);     // C_c = V_s,c K_c [Chang08 eq. 2.10]
    if (divide_by_eps) out.cell_coeff[q] /= in.eps; // Model B: F_A / eps (exchange.hpp)
  }
  if (c.scheme != ExchangeScheme::scheme2) return;
  // [Chang08 eq. 2.11]: the particle's share of F_c is its surface area over the cell's.
  for (std::size_t i = 0; i < n; ++i) {
    const long q = out.cell[i];
    const auto uq = static_cast<std::size_t>(q);
    const double d = 2.0 * p.radius[i];
    const double ci = d * d / sd2[uq] * out.cell_coeff[uq];
    out.coeff[i] = ci;
    out.eps[i] = gs.porosity()[uq];
    out.ux[i] = cell_gas_velocity(gs, q, 0);
    out.uy[i] = cell_gas_velocity(gs, q, 1);
    out.uz[i] = cell_gas_velocity(gs, q, 2);
    out.drag_x[i] = ci * (out.ux[i] - out.cell_vx[uq]);
    out.drag_y[i] = ci * (out.uy[i] - out.cell_vy[uq]);
    out.drag_z[i] = ci * (out.uz[i] - out.cell_vz[uq]);
  }
}
} // namespace

ParticleForceForm particle_force_form(const CouplingSettings& c, const gas::GasSettings& gas) {
  if (c.particle_force) return *c.particle_force;
  return gas.model == gas::PressureModel::A ? ParticleForceForm::pressure_gradient
                                            : ParticleForceForm::buoyancy;
}

void validate(const CouplingSettings& c, const gas::GasSettings& gas) {
  validate(c.porosity);
  const drag::DragModel m = drag::drag_model_named(c.drag);
  if (const auto why = drag::drag_model_refusal(m); !why.empty())
    throw InputError("coupling.drag = " + std::string(why));
  const ParticleForceForm form = particle_force_form(c, gas);
  if ((gas.model == gas::PressureModel::A) != (form == ParticleForceForm::pressure_gradient))
    throw InputError("coupling.particle_force = \"" + std::string(to_string(form)) +
                     "\" does not go with gas.model (allowed: \"pressure_gradient\" with "
                     "gas.model = \"A\"; \"buoyancy\" or \"total\" with gas.model = \"B\")");
  const bool total = form == ParticleForceForm::total;
  if (drag::is_total_force(m) != total)
    throw InputError(
        "coupling.drag = \"" + std::string(drag::to_string(m)) +
        "\" does not go with coupling.particle_force = \"" + std::string(to_string(form)) + "\": " +
        (total ? "the \"total\" form takes a closure whose force is the total gas force on a "
                 "particle, drag and pressure together (allowed: \"wen_yu_single\" "
                 "[Hoomans96 eq. 34-37]); a drag coefficient needs the pressure force of the "
                 "\"pressure_gradient\" (gas.model = \"A\") or \"buoyancy\" (\"B\") form"
               : "this closure's force is the total gas force, drag and pressure together, and "
                 "this form adds the pressure force a second time (allowed: "
                 "coupling.particle_force = \"total\" with gas.model = \"B\", or a drag "
                 "coefficient such as \"wen_yu\")"));
  if (drag::needs_mean_diameter(m) && !(c.d_mean > 0.0))
    throw InputError(std::string("coupling.d_mean must be > 0 for drag closure '") +
                     std::string(drag::to_string(m)) + "'");
}

void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c) {
  PorosityScratch scratch;
  update_porosity(gs, p, c, scratch);
}

void update_porosity(gas::GasSolver& gs, const ParticleStore& p, const CouplingSettings& c,
                     PorosityScratch& scratch, const RankSum* ranks) {
  compute_porosity(gs.grid(), p, c.porosity, gs.porosity(), periodic_axes(gs), scratch, ranks);
}

void compute_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                             const CouplingSettings& c, ParticleGasForces& out,
                             const RankSum* ranks) {
  const std::size_t n = p.size();
  for (auto* v : out.per_particle()) v->resize(n); // not zeroed: the loop below writes them all
  out.scheme = c.scheme;
  out.porosity = c.porosity;
  if (c.scheme == ExchangeScheme::scheme3) {
    out.cell.clear();
    out.cell_coeff.clear();
    out.cell_vx.clear();
    out.cell_vy.clear();
    out.cell_vz.clear();
  }
  const double mu = gs.settings().viscosity;
  const bool model_a = gs.settings().model == gas::PressureModel::A;
  // Model B divides the drag by eps [Zhu07 §3.1]; the "total" form takes the closure's force as
  // it is [Hoomans96 eq. 34].
  const bool divide_by_eps = particle_force_form(c, gs.settings()) == ParticleForceForm::buoyancy;
  const Vec3 grav = gs.settings().gravity;
  const bool stencils = c.porosity.method != PorosityMethod::porous_cube;
  const std::array<bool, 3> periodic = periodic_axes(gs);
  const gas::GasGrid& g = gs.grid();
  const bool two_d = g.dimension == 2;
  out.face_stencils.resize(stencils ? 3 * n : 0);
  if (stencils) face_pressure_differences(gs, out.face_dp);
  // The closure by name, once per call (a few string comparisons per flow step).
  drag::with_drag_closure(drag::drag_model_named(c.drag), [&](auto closure) {
    using C = decltype(closure);
    // One particle (NY = 1: 2-D, 2: 3-D stencils).
    const auto particle = [&]<int NY>(ParticleMapping& map, std::size_t i) {
      const Vec3 x = p.position(i);
      drag::DragInput in;
      const double d = 2.0 * p.radius[i];
      in.d = d; // the particle's own size for the porous cube's mapping
      Vec3 u, gp;
      if (stencils) { // [Hoomans96 eq. 40-41], the stencils kept for the rest of the step
        TrilinearStencil* st = &out.face_stencils[3 * i];
        TrilinearStencil cell; // the cell centres' (ParticleMapping::porosity_and_density's)
        trilinear_stencils(g, x, periodic, st, cell);
        velocity_and_gradient<NY>(gs, out.face_dp, st, u, gp);
        trilinear_sums<NY>(cell, g.stride[1], g.stride[2], gs.porosity().data(),
                           gs.density().data(), in.eps, in.rho);
      } else {
        map.gas_at(x, in.d, u, gp, in.eps, in.rho);
      }
      in.mu = mu;
      in.d_mean = c.d_mean;
      in.d = d * c.drag_diameter_factor; // a parcel's real particles' (coarse graining)
      const Vec3 v = p.velocity(i);
      const Vec3 slip{u[0] - v[0], u[1] - v[1], u[2] - v[2]};
      in.slip = std::sqrt(slip[0] * slip[0] + slip[1] * slip[1] + slip[2] * slip[2]);
      const double vol = pi * d * d * d / 6.0;
      double ci = vol * C::k(in);      // [Deen07 eq. 1]: F = V K (u - v)
      if (divide_by_eps) ci /= in.eps; // Model B: f_d / eps (exchange.hpp)
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
      } else { // Model B: the buoyancy term -V rho g of f_pf (exchange.hpp)
        out.pres_x[i] = -vol * in.rho * grav[0];
        out.pres_y[i] = -vol * in.rho * grav[1];
        out.pres_z[i] = -vol * in.rho * grav[2];
      }
    };
    // Independent per particle: parallel, and the same result for any thread count.
    const auto all = [&]<int NY>() {
      parallel_for_with(
          n, threaded_particles(n),
          [&] { return ParticleMapping(gs, c.porosity); }, // per thread: scratch space
          [&](ParticleMapping& map, std::size_t i) { particle.template operator()<NY>(map, i); });
    };
    if (two_d)
      all.template operator()<1>();
    else
      all.template operator()<2>();
    // Schemes 1, 2: the cell averages (scheme 2 replaces the per-particle drag above).
    if (c.scheme != ExchangeScheme::scheme3) compute_cell_forces<C>(gs, p, c, out, ranks);
  });
}

void deposit_momentum_source(gas::GasSolver& gs, const ParticleStore& p, ParticleGasForces& f,
                             const RankSum* ranks) {
  const gas::GasGrid& g = gs.grid();
  const double inv_v = 1.0 / g.cell_volume();
  const std::array<bool, 3> periodic = periodic_axes(gs);
  const bool model_b = gs.settings().model == gas::PressureModel::B;
  ParticleMapping map(gs, f.porosity);
  // With ranks: fields 3 d + (0: K, 1: K u_s, 2: src) in fixed point (rank_sum.hpp), each part
  // below its particle's c_i / V_cell, c_i |v_i| / V_cell and |pres_i| / V_cell (the weights
  // over a particle's nodes sum to 1).
  FixedPointSum* fixed = ranks ? &f.fixed : nullptr;
  if (fixed) {
    std::array<double, 9> largest{};
    for (std::size_t i = 0; i < p.size(); ++i)
      for (std::size_t d = 0; d < 3; ++d) {
        const double v = d == 0 ? p.vx[i] : (d == 1 ? p.vy[i] : p.vz[i]);
        const double pr = d == 0 ? f.pres_x[i] : (d == 1 ? f.pres_y[i] : f.pres_z[i]);
        const double c = f.scheme == ExchangeScheme::scheme3 ? std::abs(f.coeff[i]) * inv_v : 0.0;
        largest[3 * d] = nan_or_max(largest[3 * d], c);
        largest[3 * d + 1] = nan_or_max(largest[3 * d + 1], c * std::abs(v));
        largest[3 * d + 2] = nan_or_max(largest[3 * d + 2], model_b ? std::abs(pr) * inv_v : 0.0);
      }
    fixed->start(g.size(), largest, static_cast<std::int64_t>(p.size()), *ranks);
  }
  for (int d = 0; d < 3; ++d) {
    const auto fd = static_cast<std::size_t>(3 * d);
    std::vector<double>& K = gs.drag_coefficient(d);
    std::vector<double>& Kus = gs.drag_velocity_term(d);
    std::vector<double>& src = gs.explicit_source(d);
    const std::vector<unsigned char>& role = gs.face_role(d);
    K.assign(g.size(), 0.0);
    Kus.assign(g.size(), 0.0);
    src.assign(g.size(), 0.0);
    // Model B: minus the buoyancy terms, with the same weights as the drag (exchange.hpp).
    const std::vector<double>& pr = d == 0 ? f.pres_x : (d == 1 ? f.pres_y : f.pres_z);
    if (f.scheme != ExchangeScheme::scheme3) {
      // Schemes 1, 2: -F_c, half to each face of the cell along d (exchange.hpp).
      const std::vector<double>& vc = d == 0 ? f.cell_vx : (d == 1 ? f.cell_vy : f.cell_vz);
      const long st = g.stride[static_cast<std::size_t>(d)];
      // The two faces of cell q along d (periodic copies replaced by their images).
      auto faces_of = [&](std::size_t q) {
        const auto lq = static_cast<long>(q);
        return std::array<std::size_t, 2>{
            static_cast<std::size_t>(periodic_image(g, periodic, d, lq - st)),
            static_cast<std::size_t>(periodic_image(g, periodic, d, lq))};
      };
      for (std::size_t q = 0; q < f.cell_coeff.size(); ++q) {
        if (!(f.cell_coeff[q] > 0.0)) continue;
        const std::array<std::size_t, 2> faces = faces_of(q);
        const int ns =
            int(takes_particle_source(role[faces[0]])) + int(takes_particle_source(role[faces[1]]));
        if (ns == 0) continue;
        const double w = f.cell_coeff[q] * inv_v / ns;
        for (std::size_t fq : faces) {
          if (!takes_particle_source(role[fq])) continue;
          K[fq] += w;
          Kus[fq] += w * vc[q];
        }
      }
      if (model_b) // per particle, to the faces of its cell as the cell's drag
        for (std::size_t i = 0; i < p.size(); ++i) {
          const std::array<std::size_t, 2> faces = faces_of(static_cast<std::size_t>(f.cell[i]));
          const int ns = int(takes_particle_source(role[faces[0]])) +
                         int(takes_particle_source(role[faces[1]]));
          if (ns == 0) continue;
          const double w = -pr[i] * inv_v / ns;
          for (std::size_t fq : faces)
            if (takes_particle_source(role[fq])) {
              if (fixed)
                fixed->add(fd + 2, fq, w);
              else
                src[fq] += w;
            }
        }
      continue;
    }
    const std::vector<double>& v = d == 0 ? p.vx : (d == 1 ? p.vy : p.vz);
    // 1 on the faces that take the source, 0 elsewhere: the sums below then need no branch
    // (a face that takes none gets exact zeros added, the solved faces the same bits).
    std::vector<double>& takes = f.takes_source[static_cast<std::size_t>(d)];
    takes.resize(g.size());
    for (std::size_t q = 0; q < takes.size(); ++q) takes[q] = takes_particle_source(role[q]);
    // One particle's share over its weights: nodes(f) calls f(q, w) for each (index, weight)
    // in order (twice: the sum of the weights that take the source, then the shares).
    const auto deposit = [&](std::size_t i, const auto& nodes) {
      double wsum = 0.0; // over the faces that take the source, in node order
      nodes([&](long q, double w) { wsum += w * takes[static_cast<std::size_t>(q)]; });
      if (!(wsum > 0.0)) return;
      const double ci = f.coeff[i] * inv_v / wsum;
      nodes([&](long lq, double wt) {
        const auto q = static_cast<std::size_t>(lq);
        const double w = wt * ci, t = takes[q];
        if (fixed) {
          if (t == 0.0) return;
          fixed->add(fd, q, w);
          fixed->add(fd + 1, q, w * v[i]);
          if (model_b) fixed->add(fd + 2, q, -(wt * pr[i] * inv_v / wsum));
          return;
        }
        K[q] += w * t;
        Kus[q] += w * v[i] * t;
        if (model_b) src[q] -= wt * pr[i] * inv_v / wsum * t;
      });
    };
    const bool cached = f.face_stencils.size() == 3 * p.size();
    const bool any_periodic = periodic[0] || periodic[1] || periodic[2];
    const bool two_d = g.dimension == 2;
    if (two_d && d == 1) continue; // no v_y in 2-D
    const long sy = g.stride[1], sz = g.stride[2];
    for (std::size_t i = 0; i < p.size(); ++i) {
      // The weights the particle's gas velocity came from (periodic images resolved).
      if (!cached) { // the porous cube
        const CubeAxes& a = map.cube_axes_of(d, p.position(i), 2.0 * p.radius[i]);
        deposit(i, [&](const auto& fn) { for_cube_weights(g, a, d, fn); });
        continue;
      }
      // The stencil's nodes once (images resolved once), then visited twice.
      const TrilinearStencil& st = f.face_stencils[3 * i + static_cast<std::size_t>(d)];
      std::array<long, 8> qs{};
      std::array<double, 8> ws{};
      std::size_t nw = 0;
      const auto node = [&](long q, double w) {
        qs[nw] = any_periodic ? periodic_image(g, periodic, d, q) : q;
        ws[nw++] = w;
      };
      const auto visit = [&]<std::size_t N>() {
        deposit(i, [&](const auto& fn) {
          for (std::size_t m = 0; m < N; ++m) fn(qs[m], ws[m]);
        });
      };
      if (two_d) {
        for_trilinear_nodes<1>(st, sy, sz, node);
        visit.template operator()<4>();
      } else {
        for_trilinear_nodes<2>(st, sy, sz, node);
        visit.template operator()<8>();
      }
    }
  }
  if (!fixed) return;
  fixed->reduce(*ranks);
  for (int d = 0; d < 3; ++d) {
    const auto fd = static_cast<std::size_t>(3 * d);
    if (f.scheme == ExchangeScheme::scheme3) { // (schemes 1, 2: from the cells, above)
      fixed->result(fd, gs.drag_coefficient(d));
      fixed->result(fd + 1, gs.drag_velocity_term(d));
    }
    if (model_b) fixed->result(fd + 2, gs.explicit_source(d));
  }
}

void update_particle_forces(const gas::GasSolver& gs, const ParticleStore& p,
                            ParticleGasForces& f) {
  const std::size_t n = p.size();
  const bool model_a = gs.settings().model == gas::PressureModel::A;
  const bool scheme2 = f.scheme == ExchangeScheme::scheme2;
  const bool cached = f.face_stencils.size() == 3 * n;
  if (cached) face_pressure_differences(gs, f.face_dp); // the pressure of this flow step
  const bool two_d = gs.grid().dimension == 2;
  parallel_for_with(
      n, threaded_particles(n),
      [&] { return ParticleMapping(gs, f.porosity); }, // per thread: scratch space
      [&](ParticleMapping& map, std::size_t i) {
        Vec3 u, gp;
        if (cached && two_d)
          velocity_and_gradient<1>(gs, f.face_dp, &f.face_stencils[3 * i], u, gp);
        else if (cached)
          velocity_and_gradient<2>(gs, f.face_dp, &f.face_stencils[3 * i], u, gp);
        else
          map.velocity_and_pressure_gradient(p.position(i), 2.0 * p.radius[i], u, gp);
        Vec3 v = p.velocity(i);
        if (scheme2) { // s_i C_c (u_c,new - v_c): minus what the gas received [Chang08 eq. 2.11]
          const long q = f.cell[i];
          const auto uq = static_cast<std::size_t>(q);
          for (int d = 0; d < 3; ++d) u[d] = cell_gas_velocity(gs, q, d);
          v = {f.cell_vx[uq], f.cell_vy[uq], f.cell_vz[uq]};
        }
        f.ux[i] = u[0];
        f.uy[i] = u[1];
        f.uz[i] = u[2];
        f.drag_x[i] = f.coeff[i] * (u[0] - v[0]);
        f.drag_y[i] = f.coeff[i] * (u[1] - v[1]);
        f.drag_z[i] = f.coeff[i] * (u[2] - v[2]);
        if (model_a) {
          const double d = 2.0 * p.radius[i];
          const double vol = pi * d * d * d / 6.0;
          f.pres_x[i] = -vol * gp[0];
          f.pres_y[i] = -vol * gp[1];
          f.pres_z[i] = -vol * gp[2];
        }
      });
}

} // namespace fluidem::coupling
