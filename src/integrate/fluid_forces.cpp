#include "integrate/fluid_forces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/parallel.hpp"
#include "coupling/forces/fluid_torque.hpp"
#include "coupling/forces/magnus.hpp"
#include "coupling/forces/saffman_mei.hpp"
#include "coupling/forces/virtual_mass.hpp"
#include "coupling/interpolation.hpp"

namespace fluidem {

namespace {

/// grad u at x, G[i][j] = du_i/dx_j, 1/s: central differences of the interpolated velocity over
/// half a cell along each axis (points clamped into the domain, the difference divided by the
/// distance actually spanned); exact for a linear field. None along an axis the grid does not
/// resolve (one cell across: 2-D, or a 3-D column one cell deep), whose walls' ghost values
/// would otherwise read as a wall shear at every particle.
std::array<std::array<double, 3>, 3> velocity_gradient(const gas::GasSolver& gs, const Vec3& x) {
  const gas::GasGrid& g = gs.grid();
  std::array<std::array<double, 3>, 3> G{};
  for (int j = 0; j < 3; ++j) {
    const auto uj = static_cast<std::size_t>(j);
    if (g.n[uj] == 1) continue;
    const double lo = g.lo[uj], hi = g.lo[uj] + g.n[uj] * g.h[uj];
    Vec3 a = x, b = x;
    a[j] = std::max(lo, x[j] - 0.5 * g.h[uj]);
    b[j] = std::min(hi, x[j] + 0.5 * g.h[uj]);
    const double span = b[j] - a[j];
    if (!(span > 0.0)) continue;
    const Vec3 ua = coupling::gas_velocity_at(gs, a), ub = coupling::gas_velocity_at(gs, b);
    for (int i = 0; i < 3; ++i) G[static_cast<std::size_t>(i)][uj] = (ub[i] - ua[i]) / span;
  }
  return G;
}

} // namespace

FluidForces::FluidForces(const coupling::FluidForceSettings& s, const gas::GasSolver& gs,
                         double flow_dt, std::size_t n, const BodyForceSpec* field)
    : s_(s), dt_(flow_dt), rho_(gs.settings().density),
      mu_(gs.settings().viscosity), g_{gs.settings().gravity[0], gs.settings().gravity[1],
                                       gs.settings().gravity[2]},
      field_(field) {
  for (auto* a : {&held_, &physical_, &v_start_, &u_start_, &reaction_, &torque_})
    for (auto& v : *a) v.assign(n, 0.0);
  if (s_.basset)
    basset_ = std::make_unique<coupling::forces::BassetHistory>(dt_, s_.basset_window, n);
}

double FluidForces::added_inertia(double d) const {
  double m = 0.0;
  if (s_.virtual_mass) m += coupling::forces::added_mass(s_.virtual_mass_coefficient, rho_, d);
  if (s_.basset)
    m += coupling::forces::basset_added_mass(coupling::forces::basset_prefactor(d, rho_, mu_), dt_);
  return m;
}

void FluidForces::begin_step(const ParticleStore& p, const coupling::ParticleGasForces& f) {
  const std::size_t n = p.size();
  const std::array<const std::vector<double>*, 3> v{&p.vx, &p.vy, &p.vz};
  const std::array<const std::vector<double>*, 3> u{&f.ux, &f.uy, &f.uz};
  for (std::size_t i = 0; i < n; ++i) {
    const double mx = p.inv_mass[i] > 0.0 ? added_inertia(2.0 * p.radius[i]) : 0.0;
    for (std::size_t d = 0; d < 3; ++d) {
      const double vi = (*v[d])[i];
      // J / DT = F_held + m_x (g + a) - m_x (v^{n+1} - v^n) / DT: physical_ holds the first two
      // (none before the first step).
      reaction_[d][i] = started_ ? physical_[d][i] - mx * (vi - v_start_[d][i]) / dt_ : 0.0;
      v_start_[d][i] = vi;
      u_start_[d][i] = (*u[d])[i];
    }
    if (basset_) basset_->push(i, Vec3{f.ux[i] - p.vx[i], f.uy[i] - p.vy[i], f.uz[i] - p.vz[i]});
  }
}

void FluidForces::deposit_reaction(gas::GasSolver& gs, const ParticleStore& p,
                                   const coupling::RankSum* ranks) {
  if (!started_) return;
  const gas::GasGrid& g = gs.grid();
  const double inv_v = 1.0 / g.cell_volume();
  const std::array<bool, 3> periodic = coupling::periodic_axes(gs);
  // On ranks: field d in fixed point, each node's part at most |reaction_d| / V_cell (the
  // weights over a particle's nodes sum to 1).
  if (ranks) {
    std::array<double, 3> largest{};
    for (std::size_t d = 0; d < 3; ++d)
      for (std::size_t i = 0; i < p.size(); ++i) {
        const double v = std::abs(reaction_[d][i]) * inv_v;
        largest[d] = std::isnan(v) || std::isnan(largest[d]) ? v : std::max(largest[d], v);
      }
    fixed_.start(g.size(), largest, static_cast<std::int64_t>(p.size()), *ranks);
  }
  for (int d = 0; d < 3; ++d) {
    const auto ud = static_cast<std::size_t>(d);
    std::vector<double>& src = gs.explicit_source(d);
    const std::vector<unsigned char>& role = gs.face_role(d);
    for (std::size_t i = 0; i < p.size(); ++i) {
      const coupling::Stencil st = coupling::face_stencil(g, d, p.position(i));
      // The stencil's nodes that take a source (periodic images resolved), weight redistributed
      // over them as the drag's (exchange.cpp).
      std::array<std::size_t, 8> q{};
      std::array<bool, 8> takes{};
      double wsum = 0.0;
      for (std::size_t m = 0; m < static_cast<std::size_t>(st.n); ++m) {
        q[m] = static_cast<std::size_t>(coupling::periodic_image(g, periodic, d, st.q[m]));
        takes[m] = coupling::takes_particle_source(role[q[m]]);
        if (takes[m]) wsum += st.w[m];
      }
      if (!(wsum > 0.0)) continue;
      const double share = -reaction_[ud][i] * inv_v / wsum;
      for (std::size_t m = 0; m < static_cast<std::size_t>(st.n); ++m)
        if (takes[m]) {
          if (ranks)
            fixed_.add(ud, q[m], st.w[m] * share);
          else
            src[q[m]] += st.w[m] * share;
        }
    }
  }
  if (!ranks) return;
  fixed_.reduce(*ranks);
  std::vector<double> sum;
  for (int d = 0; d < 3; ++d) {
    fixed_.result(static_cast<std::size_t>(d), sum);
    std::vector<double>& src = gs.explicit_source(d);
    for (std::size_t q = 0; q < sum.size(); ++q) src[q] += sum[q];
  }
}

void FluidForces::compute(const gas::GasSolver& gs, const ParticleStore& p,
                          const coupling::ParticleGasForces& f) {
  const std::size_t n = p.size();
  const bool lift = s_.saffman || s_.magnus != "off" || s_.torque != "off";
  const bool dennis = s_.torque == "dennis";
  const bool magnus_rk = s_.magnus == "rubinow_keller";
  const bool magnus_ob = s_.magnus == "oesterle_bui_dinh";
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    for (std::size_t d = 0; d < 3; ++d) held_[d][i] = physical_[d][i] = torque_[d][i] = 0.0;
    if (p.inv_mass[i] == 0.0) return; // fixed: no force acts
    const double d = 2.0 * p.radius[i];
    const Vec3 x = p.position(i);
    const Vec3 u{f.ux[i], f.uy[i], f.uz[i]};
    const Vec3 v{v_start_[0][i], v_start_[1][i], v_start_[2][i]};
    const Vec3 w{u[0] - v[0], u[1] - v[1], u[2] - v[2]};
    std::array<std::array<double, 3>, 3> G{};
    if (lift || s_.virtual_mass) G = velocity_gradient(gs, x);
    const Vec3 omega{G[2][1] - G[1][2], G[0][2] - G[2][0], G[1][0] - G[0][1]};
    Vec3 F{0.0, 0.0, 0.0};
    if (s_.saffman) F = F + coupling::forces::saffman_mei_lift(w, omega, d, rho_, mu_);
    if (magnus_rk || magnus_ob) {
      const Vec3 spin = p.angular_velocity(i);
      F = F + (magnus_rk ? coupling::forces::magnus_rubinow_keller(w, omega, spin, d, rho_)
                         : coupling::forces::magnus_oesterle(w, omega, spin, d, rho_, mu_));
    }
    if (s_.torque != "off") { // k (Omega/2 - omega^n), the exact mean over the step (header)
      const Vec3 spin = p.angular_velocity(i);
      const Vec3 t = dennis ? coupling::forces::fluid_torque_dennis(omega, spin, d, rho_, mu_)
                            : coupling::forces::fluid_torque_stokes(omega, spin, d, mu_);
      // k = |T| / |Omega/2 - omega| (the torque is along the relative spin in both models)
      const double rel = norm(coupling::forces::relative_spin(omega, spin));
      const double kdt = rel > 0.0 ? norm(t) / rel * dt_ * p.inv_inertia[i] : 0.0;
      const double mean = kdt > 1e-8 ? -std::expm1(-kdt) / kdt : 1.0 - 0.5 * kdt;
      for (int a = 0; a < 3; ++a) torque_[static_cast<std::size_t>(a)][i] = t[a] * mean;
    }
    if (s_.virtual_mass) { // m_a Du/Dt; its -m_a dv/dt is the added inertia
      const double ma = coupling::forces::added_mass(s_.virtual_mass_coefficient, rho_, d);
      for (int a = 0; a < 3; ++a) {
        const auto ua = static_cast<std::size_t>(a);
        double dudt = (u[a] - u_start_[ua][i]) / dt_;
        for (std::size_t b = 0; b < 3; ++b) dudt += G[ua][b] * u[static_cast<int>(b)];
        F[a] += ma * dudt;
      }
    }
    if (basset_) { // K_B [c_new (u^{n+1} - v^n) + H]; its -K_B c_new (v^{n+1} - v^n): inertia
      const double kb = coupling::forces::basset_prefactor(d, rho_, mu_);
      F = F + kb * basset_->integral(i, w);
    }
    const double mx = added_inertia(d);
    std::array<double, 3> acc = g_; // what the kick gives every unit of the particle's mass
    if (field_ != nullptr) {
      const auto b = body_acceleration(*field_, x[0], x[1], x[2]);
      for (std::size_t a = 0; a < 3; ++a) acc[a] += b[a];
    }
    for (std::size_t a = 0; a < 3; ++a) {
      physical_[a][i] = F[static_cast<int>(a)];
      held_[a][i] = F[static_cast<int>(a)] - mx * acc[a];
    }
  });
  started_ = true;
}

std::vector<std::pair<std::string, std::vector<double>>> FluidForces::state() const {
  std::vector<std::pair<std::string, std::vector<double>>> s;
  const char* axes = "xyz";
  for (std::size_t d = 0; d < 3; ++d) {
    const std::string a(1, axes[d]);
    s.emplace_back("held_" + a, held_[d]);
    s.emplace_back("physical_" + a, physical_[d]);
    s.emplace_back("v_start_" + a, v_start_[d]);
    s.emplace_back("u_start_" + a, u_start_[d]);
    s.emplace_back("reaction_" + a, reaction_[d]);
    s.emplace_back("torque_" + a, torque_[d]);
  }
  s.emplace_back("started", std::vector<double>{started_ ? 1.0 : 0.0});
  if (basset_) {
    const coupling::forces::BassetHistory::State b = basset_->state();
    s.emplace_back("basset_count", std::vector<double>(b.count.begin(), b.count.end()));
    s.emplace_back("basset_samples", b.samples);
    s.emplace_back("basset_start_slip", b.start_slip);
    s.emplace_back("basset_tail", b.tail);
  }
  return s;
}

void FluidForces::restore(const std::vector<std::pair<std::string, std::vector<double>>>& s) {
  auto get = [&](const std::string& name) -> const std::vector<double>& {
    for (const auto& [k, v] : s)
      if (k == name) return v;
    throw std::runtime_error("checkpoint: no fluid-force state '" + name + "'");
  };
  const char* axes = "xyz";
  for (std::size_t d = 0; d < 3; ++d) {
    const std::string a(1, axes[d]);
    held_[d] = get("held_" + a);
    physical_[d] = get("physical_" + a);
    v_start_[d] = get("v_start_" + a);
    u_start_[d] = get("u_start_" + a);
    reaction_[d] = get("reaction_" + a);
    torque_[d] = get("torque_" + a);
  }
  started_ = get("started").at(0) != 0.0;
  if (basset_) { // the sample counts are whole numbers below 2^53: exact as doubles
    coupling::forces::BassetHistory::State b;
    b.dt = basset_->dt();
    b.window = basset_->window();
    for (const double c : get("basset_count")) b.count.push_back(static_cast<std::uint64_t>(c));
    b.samples = get("basset_samples");
    b.start_slip = get("basset_start_slip");
    b.tail = get("basset_tail");
    basset_->set_state(b);
  }
}

namespace {
/// The per-particle arrays of FluidForces::state() and their numbers per particle, in its order
/// ("started", a scalar, is not one).
std::vector<std::pair<std::string, std::size_t>>
particle_arrays(const coupling::FluidForceSettings& s) {
  std::vector<std::pair<std::string, std::size_t>> a;
  for (const char* axis : {"x", "y", "z"})
    for (const char* name : {"held_", "physical_", "v_start_", "u_start_", "reaction_", "torque_"})
      a.emplace_back(std::string(name) + axis, 1);
  if (s.basset) {
    const auto ring = static_cast<std::size_t>(s.basset_window) + 1;
    a.emplace_back("basset_count", 1);
    a.emplace_back("basset_samples", 3 * ring);
    a.emplace_back("basset_start_slip", 3);
    a.emplace_back("basset_tail", 3 * coupling::forces::BassetHistory::tail_terms);
  }
  return a;
}
} // namespace

std::size_t FluidForces::width(const coupling::FluidForceSettings& s) {
  std::size_t w = 0;
  for (const auto& [name, k] : particle_arrays(s)) w += k;
  return w;
}

// The numbers of a particle in the order of particle_arrays(): per axis held, physical,
// v_start, u_start, reaction, torque; then its Basset history (BassetHistory::save_particle).
void FluidForces::save(std::span<double> out) const {
  const std::size_t n = held_[0].size(), w = width(s_);
  if (out.size() != n * w)
    throw std::logic_error("FluidForces::save: room for " + std::to_string(out.size()) +
                           " numbers, " + std::to_string(n) + " particles of " + std::to_string(w));
  for (std::size_t i = 0; i < n; ++i) {
    double* o = out.data() + w * i;
    for (std::size_t d = 0; d < 3; ++d) {
      double* od = o + 6 * d;
      od[0] = held_[d][i], od[1] = physical_[d][i], od[2] = v_start_[d][i];
      od[3] = u_start_[d][i], od[4] = reaction_[d][i], od[5] = torque_[d][i];
    }
    if (basset_) basset_->save_particle(i, o + 18);
  }
}

void FluidForces::load(std::span<const double> in, std::size_t n) {
  const std::size_t w = width(s_);
  if (in.size() != n * w)
    throw std::logic_error("FluidForces::load: " + std::to_string(in.size()) + " numbers for " +
                           std::to_string(n) + " particles of " + std::to_string(w));
  for (auto* a : {&held_, &physical_, &v_start_, &u_start_, &reaction_, &torque_})
    for (auto& v : *a) v.resize(n);
  if (basset_) basset_->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double* o = in.data() + w * i;
    for (std::size_t d = 0; d < 3; ++d) {
      const double* od = o + 6 * d;
      held_[d][i] = od[0], physical_[d][i] = od[1], v_start_[d][i] = od[2];
      u_start_[d][i] = od[3], reaction_[d][i] = od[4], torque_[d][i] = od[5];
    }
    if (basset_) basset_->load_particle(i, o + 18);
  }
}

std::vector<std::pair<std::string, std::vector<double>>>
FluidForces::unpacked(const std::vector<double>& in, std::size_t n) const {
  const std::size_t w = width(s_);
  if (in.size() != n * w)
    throw std::logic_error("FluidForces::unpacked: " + std::to_string(in.size()) + " numbers for " +
                           std::to_string(n) + " particles of " + std::to_string(w));
  std::vector<std::pair<std::string, std::vector<double>>> st;
  std::size_t offset = 0;
  for (const auto& [name, k] : particle_arrays(s_)) {
    std::vector<double> v(n * k);
    for (std::size_t i = 0; i < n; ++i)
      std::copy_n(in.begin() + static_cast<std::ptrdiff_t>(w * i + offset), k,
                  v.begin() + static_cast<std::ptrdiff_t>(k * i));
    st.emplace_back(name, std::move(v));
    offset += k;
  }
  st.emplace_back("started", std::vector<double>{started_ ? 1.0 : 0.0});
  return st;
}

void FluidForces::permute(const std::vector<std::uint32_t>& new_to_old) {
  for (auto* a : {&held_, &physical_, &v_start_, &u_start_, &reaction_, &torque_})
    for (std::vector<double>& v : *a) {
      if (v.size() != new_to_old.size()) continue;
      const std::vector<double> old = v;
      for (std::size_t k = 0; k < new_to_old.size(); ++k) v[k] = old[new_to_old[k]];
    }
  if (basset_) basset_->permute(new_to_old);
}

} // namespace fluidem
