#include "contact/contact_forces.hpp"

#include <algorithm>
#include <cmath>

#include "contact/kernels/history_rotation.hpp"
#include "contact/kernels/normal_force.hpp"
#include "contact/kernels/rolling_torque.hpp"
#include "contact/kernels/tangential_force.hpp"

namespace fluidem {

int contact_history_width(const ContactTable& t) {
  return (t.tangential() == TangentialModel::History ? 3 : 0) +
         (t.rolling() == RollingModel::SpringDashpot ? 3 : 0);
}

namespace {

/// One contact between particle i and partner b (a particle or a wall of infinite mass).
struct ContactInput {
  Vec3 n;                    ///< unit normal from i towards the partner
  Vec3 d_prev;               ///< separation one step earlier, unnormalised (rotates the history)
  bool fixed_normal = false; ///< wall contact: the normal never turns
  double overlap;            ///< m, > 0
  Vec3 v_rel; ///< contact-point velocity of i relative to the partner [Deen07 eq. 12]
  Vec3 w_rel; ///< w_i - w_partner
  double r_eff, m_eff, inv_inertia_sum;
};

struct ContactOutput {
  Vec3 force;       ///< on i
  Vec3 torque_unit; ///< n x F_t: torque on i is r_i * this, on a partner particle r_j * this
  Vec3 torque_roll; ///< rolling torque on i (partner gets the opposite)
  Vec3 nc_force, nc_torque_unit, nc_torque_roll; ///< the non-conservative parts of the above
  double fn_abs = 0.0;
  double elastic = 0.0, spring_loss = 0.0;
};

template <NormalModel Normal, bool Tangential, RollingModel Rolling>
[[gnu::always_inline]] inline ContactOutput evaluate(const ContactInput& c, const PairParams& pp,
                                                     double* hist, double dt) {
  ContactOutput out;
  // Normal force [Deen07 eq. 24-27] or Hertz-Tsuji [Chang08 eq. 2.15, 2.22].
  kernels::NormalResponse nr;
  double k_tangent_ref; // normal stiffness used to scale rolling springs
  if constexpr (Normal == NormalModel::Linear) {
    nr = kernels::linear_normal(pp.kn, pp.normal_damping, c.m_eff, c.overlap);
    k_tangent_ref = pp.kn;
  } else {
    const double k_hertz = pp.kn * std::sqrt(c.r_eff);
    nr = kernels::hertz_normal(k_hertz, pp.normal_damping, c.m_eff, c.overlap);
    k_tangent_ref = nr.stiffness;
  }
  const double vn = dot(c.v_rel, c.n); // > 0 when approaching
  const double fn = nr.elastic + nr.damping_coeff * vn;
  out.force = c.n * (-fn);
  // The Coulomb and rolling limits scale with the compressive load. The dashpot makes the normal
  // force briefly tensile at the end of a damped contact; [Deen07 eq. 28] writes |F_n|, which
  // would let friction act on a pulling contact (J_t/J_n = 1.002 mu at e = 0.9), so the tensile
  // part is not counted.
  out.fn_abs = fn > 0.0 ? fn : 0.0;
  out.elastic = nr.energy;
  out.nc_force = c.n * (-nr.damping_coeff * vn);

  // The previous normal is only needed (one sqrt) when there is history to rotate.
  auto previous_normal = [&c]() { return c.d_prev / norm(c.d_prev); };
  if constexpr (Tangential) {
    // [Deen07 eq. 28-32]
    const Vec3 v_t = c.v_rel - c.n * vn;
    Vec3 delta{hist[0], hist[1], hist[2]};
    if (!c.fixed_normal && norm2(delta) > 0.0)
      delta = kernels::rotate_with_contact(delta, previous_normal(), c.n);
    const double k_t =
        (Normal == NormalModel::Linear) ? pp.kt : pp.kt * std::sqrt(c.r_eff * c.overlap);
    const double eta_t = pp.tangential_damping * std::sqrt(2.0 / 7.0 * c.m_eff * k_t);
    const auto tr = kernels::tangential_spring(delta, v_t, k_t, eta_t, pp.mu, out.fn_abs, dt);
    hist[0] = delta.x, hist[1] = delta.y, hist[2] = delta.z;
    out.force += tr.force;
    out.torque_unit = cross(c.n, tr.force);
    out.nc_force += tr.nonconservative;
    out.nc_torque_unit = cross(c.n, tr.nonconservative);
    out.elastic += tr.energy;
    out.spring_loss += tr.spring_loss;
  }
  if constexpr (Rolling != RollingModel::None) {
    // [Zhu07 Table 1], methods 2 and 1.
    const Vec3 w_roll = c.w_rel - c.n * dot(c.w_rel, c.n);
    kernels::RollingResult rr;
    if constexpr (Rolling == RollingModel::ConstantTorque) {
      rr = kernels::rolling_constant_torque(w_roll, pp.mu_r, c.r_eff, out.fn_abs, c.inv_inertia_sum,
                                            dt);
    } else {
      double* th = hist + (Tangential ? 3 : 0);
      Vec3 theta{th[0], th[1], th[2]};
      if (!c.fixed_normal && norm2(theta) > 0.0)
        theta = kernels::rotate_with_contact(theta, previous_normal(), c.n);
      const double k_r = 2.25 * k_tangent_ref * pp.mu_r * pp.mu_r * c.r_eff * c.r_eff;
      const double c_r = pp.rolling_damping * std::sqrt(k_r / c.inv_inertia_sum);
      rr = kernels::rolling_spring_dashpot(theta, w_roll, k_r, c_r, pp.mu_r, c.r_eff, out.fn_abs,
                                           dt);
      th[0] = theta.x, th[1] = theta.y, th[2] = theta.z;
    }
    out.torque_roll = rr.torque;
    out.nc_torque_roll = rr.nonconservative;
    out.elastic += rr.energy;
    out.spring_loss += rr.spring_loss;
  }
  return out;
}

template <NormalModel Normal, bool Tangential, RollingModel Rolling>
ContactStats compute(ParticleStore& p, NeighbourList& nl, const ContactTable& table, double dt,
                     NonconservativeForces& nc, ContactRecord* rec) {
  ContactStats st;
  const bool recording = rec != nullptr && rec->enabled;
  const int hw = nl.history_width();
  // A contact that ends takes its spring energy with it: count it as dissipated. (Hertz springs
  // have k_t -> 0 as the overlap closes, so only the linear springs hold energy at separation.)
  auto release = [&](ContactStats& acc, double* hist, const PairParams& pp, double r_eff) {
    bool loaded = false;
    for (int k = 0; k < hw; ++k) loaded |= hist[k] != 0.0;
    if (!loaded) return;
    if constexpr (Normal == NormalModel::Linear) {
      if constexpr (Tangential) {
        acc.spring_losses +=
            0.5 * pp.kt * (hist[0] * hist[0] + hist[1] * hist[1] + hist[2] * hist[2]);
      }
      if constexpr (Rolling == RollingModel::SpringDashpot) {
        const double* th = hist + (Tangential ? 3 : 0);
        const double k_r = 2.25 * pp.kn * pp.mu_r * pp.mu_r * r_eff * r_eff;
        acc.spring_losses += 0.5 * k_r * (th[0] * th[0] + th[1] * th[1] + th[2] * th[2]);
      }
    }
    std::fill_n(hist, hw, 0.0);
  };
  const std::size_t n = p.size();
  auto track_overlap = [&](ContactStats& acc, double ratio, std::size_t i) {
    if (ratio > acc.max_overlap_ratio) {
      acc.max_overlap_ratio = ratio;
      acc.max_overlap_particle = p.id[i];
    }
  };
  // Particle-particle pairs (half list: each pair once, forces applied to both). The rows of a
  // slab write only to particles of that slab and the next, so all even slabs run in parallel,
  // then all odd slabs; each slab runs its rows in a fixed order and keeps its own statistics,
  // summed in slab order: the result does not depend on the number of threads.
  auto process_row = [&](std::size_t i, ContactStats& acc, std::vector<ContactSample>* buf) {
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i], ri = p.radius[i];
    for (std::uint32_t e = nl.offset[i]; e < nl.offset[i + 1]; ++e) {
      const std::uint32_t j = nl.partner[e];
      const double dx = nl.min_image(p.x[j] - xi, 0);
      const double dy = nl.min_image(p.y[j] - yi, 1);
      const double dz = nl.min_image(p.z[j] - zi, 2);
      const double rsum = ri + p.radius[j];
      const double d2 = dx * dx + dy * dy + dz * dz;
      double* hist = hw ? &nl.history[static_cast<std::size_t>(e) * hw] : nullptr;
      if (d2 >= rsum * rsum) {
        if (hw) { // contact lost: history reset
          const double rj = p.radius[j];
          release(acc, hist, table.pair(p.species[i], p.species[j]), ri * rj / rsum);
        }
        continue;
      }
      const double d = std::sqrt(d2);
      ContactInput c;
      c.n = Vec3{dx, dy, dz} / d;
      c.overlap = rsum - d;
      const Vec3 vi = p.velocity(i), vj = p.velocity(j);
      const Vec3 wi = p.angular_velocity(i), wj = p.angular_velocity(j);
      const double rj = p.radius[j];
      c.v_rel = vi - vj + cross(wi * ri + wj * rj, c.n);
      c.w_rel = wi - wj;
      c.r_eff = ri * rj / rsum;
      c.m_eff = p.mass[i] * p.mass[j] / (p.mass[i] + p.mass[j]);
      c.inv_inertia_sum = p.inv_inertia[i] + p.inv_inertia[j];
      // Separation one step earlier: positions moved by v dt with the current velocities.
      c.d_prev = Vec3{dx, dy, dz} - (vj - vi) * dt;
      const auto out = evaluate<Normal, Tangential, Rolling>(
          c, table.pair(p.species[i], p.species[j]), hist, dt);
      p.fx[i] += out.force.x, p.fy[i] += out.force.y, p.fz[i] += out.force.z;
      p.fx[j] -= out.force.x, p.fy[j] -= out.force.y, p.fz[j] -= out.force.z;
      const Vec3 ti = out.torque_unit * ri + out.torque_roll;
      const Vec3 tj = out.torque_unit * rj - out.torque_roll;
      p.tx[i] += ti.x, p.ty[i] += ti.y, p.tz[i] += ti.z;
      p.tx[j] += tj.x, p.ty[j] += tj.y, p.tz[j] += tj.z;
      nc.fx[i] += out.nc_force.x, nc.fy[i] += out.nc_force.y, nc.fz[i] += out.nc_force.z;
      nc.fx[j] -= out.nc_force.x, nc.fy[j] -= out.nc_force.y, nc.fz[j] -= out.nc_force.z;
      const Vec3 nti = out.nc_torque_unit * ri + out.nc_torque_roll;
      const Vec3 ntj = out.nc_torque_unit * rj - out.nc_torque_roll;
      nc.tx[i] += nti.x, nc.ty[i] += nti.y, nc.tz[i] += nti.z;
      nc.tx[j] += ntj.x, nc.ty[j] += ntj.y, nc.tz[j] += ntj.z;
      ++acc.n_contacts;
      acc.elastic_energy += out.elastic;
      acc.spring_losses += out.spring_loss;
      track_overlap(acc, c.overlap / (2.0 * std::min(ri, rj)), i);
      if (buf) {
        ContactSample& cs = buf->emplace_back();
        cs.id_i = p.id[i];
        cs.id_j = p.id[j];
        cs.i = static_cast<std::int32_t>(i);
        cs.j = static_cast<std::int32_t>(j);
        cs.overlap = c.overlap;
        cs.normal = c.n;
        cs.force = out.force;
        cs.torque_roll = out.torque_roll;
        cs.contact_point = Vec3{xi, yi, zi} + c.n * (ri - 0.5 * c.overlap);
      }
    }
  };
  const int nslab = nl.slab_count();
  std::vector<ContactStats> slab_stats(nslab);
  // Recording: one buffer per slab (a slab runs on one thread), concatenated in slab order.
  std::vector<std::vector<ContactSample>> slab_samples(recording ? nslab : 0);
  for (int phase = 0; phase < 2; ++phase) {
#pragma omp parallel for schedule(dynamic, 1) if (n > 4096)
    for (int sl = phase; sl < nslab; sl += 2) {
      std::vector<ContactSample>* buf = recording ? &slab_samples[sl] : nullptr;
      for (std::uint32_t k = nl.slab_start[sl]; k < nl.slab_start[sl + 1]; ++k)
        process_row(nl.slab_particles[k], slab_stats[sl], buf);
    }
  }
  if (recording) {
    std::size_t total = 0;
    for (const auto& b : slab_samples) total += b.size();
    rec->samples.reserve(total + nl.wall_particle.size());
    for (const auto& b : slab_samples) rec->samples.insert(rec->samples.end(), b.begin(), b.end());
  }
  for (const auto& ss : slab_stats) {
    st.n_contacts += ss.n_contacts;
    st.elastic_energy += ss.elastic_energy;
    st.spring_losses += ss.spring_losses;
    if (ss.max_overlap_ratio > st.max_overlap_ratio) {
      st.max_overlap_ratio = ss.max_overlap_ratio;
      st.max_overlap_particle = ss.max_overlap_particle;
    }
  }
  // Particle-wall contacts: wall of infinite mass, its own material.
  const auto& box = nl.box();
  const std::array<const std::vector<double>*, 3> pos{&p.x, &p.y, &p.z};
  for (std::size_t e = 0; e < nl.wall_particle.size(); ++e) {
    const std::uint32_t i = nl.wall_particle[e];
    const int f = nl.wall_face[e];
    const int a = f / 2;
    const bool lo_face = (f % 2 == 0);
    const double ri = p.radius[i];
    const double gap = lo_face ? (*pos[a])[i] - box.lo[a] : box.hi[a] - (*pos[a])[i];
    double* hist = hw ? &nl.wall_history[e * hw] : nullptr;
    if (gap >= ri) {
      if (hw) release(st, hist, table.wall(p.species[i], f), ri);
      continue;
    }
    ContactInput c;
    c.n = Vec3{};
    c.n[a] = lo_face ? -1.0 : 1.0; // from the particle towards the wall
    c.fixed_normal = true;
    c.overlap = ri - gap;
    const Vec3 wi = p.angular_velocity(i);
    c.v_rel = p.velocity(i) + cross(wi * ri, c.n);
    c.w_rel = wi;
    c.r_eff = ri;
    c.m_eff = p.mass[i];
    c.inv_inertia_sum = p.inv_inertia[i];
    const auto out =
        evaluate<Normal, Tangential, Rolling>(c, table.wall(p.species[i], f), hist, dt);
    p.fx[i] += out.force.x, p.fy[i] += out.force.y, p.fz[i] += out.force.z;
    const Vec3 ti = out.torque_unit * ri + out.torque_roll;
    p.tx[i] += ti.x, p.ty[i] += ti.y, p.tz[i] += ti.z;
    nc.fx[i] += out.nc_force.x, nc.fy[i] += out.nc_force.y, nc.fz[i] += out.nc_force.z;
    const Vec3 nti = out.nc_torque_unit * ri + out.nc_torque_roll;
    nc.tx[i] += nti.x, nc.ty[i] += nti.y, nc.tz[i] += nti.z;
    ++st.n_contacts;
    st.elastic_energy += out.elastic;
    st.spring_losses += out.spring_loss;
    track_overlap(st, c.overlap / (2.0 * ri), i);
    if (recording) {
      ContactSample& cs = rec->samples.emplace_back();
      cs.id_i = p.id[i];
      cs.id_j = -1 - f;
      cs.i = static_cast<std::int32_t>(i);
      cs.j = -1;
      cs.overlap = c.overlap;
      cs.normal = c.n;
      cs.force = out.force;
      cs.torque_roll = out.torque_roll;
      cs.contact_point = p.position(i) + c.n * gap; // on the wall plane
    }
  }
  return st;
}

template <NormalModel Normal, bool Tangential>
ContactStats dispatch_rolling(ParticleStore& p, NeighbourList& nl, const ContactTable& t, double dt,
                              NonconservativeForces& nc, ContactRecord* rec) {
  switch (t.rolling()) {
  case RollingModel::None:
    return compute<Normal, Tangential, RollingModel::None>(p, nl, t, dt, nc, rec);
  case RollingModel::ConstantTorque:
    return compute<Normal, Tangential, RollingModel::ConstantTorque>(p, nl, t, dt, nc, rec);
  case RollingModel::SpringDashpot:
    return compute<Normal, Tangential, RollingModel::SpringDashpot>(p, nl, t, dt, nc, rec);
  }
  return {};
}

template <NormalModel Normal>
ContactStats dispatch_tangential(ParticleStore& p, NeighbourList& nl, const ContactTable& t,
                                 double dt, NonconservativeForces& nc, ContactRecord* rec) {
  return t.tangential() == TangentialModel::History
             ? dispatch_rolling<Normal, true>(p, nl, t, dt, nc, rec)
             : dispatch_rolling<Normal, false>(p, nl, t, dt, nc, rec);
}

} // namespace

void NonconservativeForces::reset(std::size_t n) {
  for (auto* v : {&fx, &fy, &fz, &tx, &ty, &tz}) v->assign(n, 0.0);
}

double NonconservativeForces::dissipated(const ParticleStore& p, double dt) const {
  double w = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    w += fx[i] * p.vx[i] + fy[i] * p.vy[i] + fz[i] * p.vz[i];
    w += tx[i] * p.wx[i] + ty[i] * p.wy[i] + tz[i] * p.wz[i];
  }
  return -w * dt;
}

ContactStats compute_contact_forces(ParticleStore& p, NeighbourList& nl, const ContactTable& t,
                                    double dt, NonconservativeForces& nc, ContactRecord* rec) {
  nc.reset(p.size());
  if (rec && rec->enabled) rec->samples.clear(); // also for a model that computes nothing
  switch (t.normal()) {
  case NormalModel::Linear:
    return dispatch_tangential<NormalModel::Linear>(p, nl, t, dt, nc, rec);
  case NormalModel::Hertz:
    return dispatch_tangential<NormalModel::Hertz>(p, nl, t, dt, nc, rec);
  case NormalModel::WaltonBraun:
    break; // rejected when the ContactTable was built
  }
  return {};
}

} // namespace fluidem
