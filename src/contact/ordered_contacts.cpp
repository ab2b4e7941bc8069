#include "contact/ordered_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <omp.h>
#include <stdexcept>
#include <string>

#include "contact/contact_evaluate.hpp"
#include "contact/models/model_list.hpp"
#include "core/parallel.hpp"

namespace fluidem {

namespace {

using contact_models::ContactInput;
using contact_models::ContactOutput;

/// The stats of one contact added to a rank's (the deepest overlap: ties go to the lower id).
void add_contact(OrderedContactStats& st, double ratio, std::int64_t id, const Vec3& f) {
  ++st.contacts;
  if (ratio > st.max_overlap_ratio ||
      (ratio == st.max_overlap_ratio && st.deepest_id >= 0 && id < st.deepest_id && ratio > 0.0))
    st.max_overlap_ratio = ratio, st.deepest_id = id;
  st.max_force2 = std::max(st.max_force2, f.x * f.x + f.y * f.y + f.z * f.z);
}

void join(OrderedContactStats& st, const OrderedContactStats& o) {
  st.contacts += o.contacts;
  if (o.max_overlap_ratio > st.max_overlap_ratio ||
      (o.max_overlap_ratio == st.max_overlap_ratio && o.deepest_id >= 0 &&
       (st.deepest_id < 0 || o.deepest_id < st.deepest_id)))
    st.max_overlap_ratio = o.max_overlap_ratio, st.deepest_id = o.deepest_id;
  st.max_force2 = std::max(st.max_force2, o.max_force2);
}

/// A contact's share of particle i's twelve sums: sign +1 when i is the contact's first body
/// (the pair's lower id, or the particle of a wall contact), -1 when it is the second; r its
/// radius (the torque arm). The torques of a model without them are not added (adding their
/// zeros would leave the sums as they are: they start at +0).
template <bool Tangential, bool Rolling>
[[gnu::always_inline]] inline void add_share(double* a, const ContactOutput& out, double r,
                                             double sign) {
  a[0] += out.force.x * sign, a[1] += out.force.y * sign, a[2] += out.force.z * sign;
  a[6] += out.nc_force.x * sign, a[7] += out.nc_force.y * sign, a[8] += out.nc_force.z * sign;
  if constexpr (Tangential || Rolling) {
    Vec3 t = out.torque_unit * r, tnc = out.nc_torque_unit * r;
    if constexpr (Rolling) {
      t = sign > 0.0 ? t + out.torque_roll : t - out.torque_roll;
      tnc = sign > 0.0 ? tnc + out.nc_torque_roll : tnc - out.nc_torque_roll;
    }
    a[3] += t.x, a[4] += t.y, a[5] += t.z;
    a[9] += tnc.x, a[10] += tnc.y, a[11] += tnc.z;
  }
}

// Record: whether the contacts are recorded (a template argument, so that the loop without the
// record is the loop as it was, without the record's code in it).
template <class Normal, class Tangential, class Rolling, bool Record>
OrderedContactStats compute(const ParticleStore& p, OrderedRows& rows, const ContactTable& table,
                            double dt, OrderedContactSums& sums,
                            std::vector<KeyedContact>* record) {
  constexpr int hw = contact_kernel::kHistoryWidth<Normal, Tangential, Rolling>;
  if (rows.history_width() != hw)
    throw std::logic_error("ordered contact loop: the rows keep " +
                           std::to_string(rows.history_width()) + " history values, the model " +
                           std::to_string(hw));
  const std::size_t owned = rows.owned();
  sums.acc.assign(OrderedContactSums::kAcc * owned, 0.0);
  sums.elastic.assign(owned, 0.0);
  sums.released.assign(owned, 0.0);
  const BoxGeometry& box = rows.box();
  const auto loaded = [](const double* h) {
    for (int m = 0; m < hw; ++m)
      if (h[m] != 0.0) return true;
    return false;
  };
  const auto row = [&](std::size_t i, OrderedContactStats& st, std::vector<KeyedContact>* rec) {
    double* a = sums.acc.data() + OrderedContactSums::kAcc * i;
    double elastic = 0.0, released = 0.0;
    const std::int64_t id_i = p.id[i];
    const double xi = p.x[i], yi = p.y[i], zi = p.z[i], r_own = p.radius[i];
    for (std::uint32_t e = rows.offset[i]; e < rows.offset[i + 1]; ++e) {
      const std::uint32_t j = rows.partner[e];
      // Most entries do not touch: tested from i's side first (the same bits as from the lower
      // id's: a - b = -(b - a) exactly, min_image is odd, and the squares and sums do not see
      // the sign or the order of the radii).
      if constexpr (!contact_kernel::adhesive<Normal>) {
        const double dx = rows.min_image(p.x[j] - xi, 0), dy = rows.min_image(p.y[j] - yi, 1),
                     dz = rows.min_image(p.z[j] - zi, 2);
        const double rs = r_own + p.radius[j];
        if (!(dx * dx + dy * dy + dz * dz < rs * rs)) {
          double* hist = rows.history.data() + static_cast<std::size_t>(e) * hw;
          if (hw > 0 && loaded(hist)) {
            const bool lower = id_i < p.id[j];
            const std::size_t ia = lower ? i : j, ib = lower ? j : i;
            double loss = 0.0;
            contact_kernel::add_released_energy<Normal, Tangential, Rolling>(
                loss, hist, table.pair(p.species[ia], p.species[ib]),
                p.radius[ia] * p.radius[ib] / (p.radius[ia] + p.radius[ib]));
            if (lower) released += loss;
            std::fill_n(hist, hw, 0.0);
          }
          continue;
        }
      }
      const bool first = id_i < p.id[j]; // i is the pair's lower id
      // The pair from its lower id's side: body a, partner b.
      const std::size_t ia = first ? i : j, ib = first ? j : i;
      const Vec3 dvec{rows.min_image(p.x[ib] - p.x[ia], 0), rows.min_image(p.y[ib] - p.y[ia], 1),
                      rows.min_image(p.z[ib] - p.z[ia], 2)};
      const double ri = p.radius[ia], rj = p.radius[ib], rsum = ri + rj;
      const double d2 = norm2(dvec);
      double* hist = rows.history.data() + static_cast<std::size_t>(e) * hw;
      const PairParams& pp = table.pair(p.species[ia], p.species[ib]);
      const bool touching =
          contact_kernel::attached_pair<Normal>(d2 < rsum * rsum, hist, pp, ri, rj, d2);
      if (!touching) {
        if (hw > 0 && loaded(hist)) {
          double loss = 0.0;
          contact_kernel::add_released_energy<Normal, Tangential, Rolling>(loss, hist, pp,
                                                                           ri * rj / rsum);
          if (first) released += loss;
          std::fill_n(hist, hw, 0.0);
        }
        continue;
      }
      // [Deen07 eq. 12] as the batched loop (contact_forces.cpp, evaluate_batch) writes it.
      const double inv_mi = p.inv_mass[ia], inv_mj = p.inv_mass[ib];
      const Vec3 dv{p.vx[ia] - p.vx[ib], p.vy[ia] - p.vy[ib], p.vz[ia] - p.vz[ib]};
      const Vec3 wi{p.wx[ia], p.wy[ia], p.wz[ia]}, wj{p.wx[ib], p.wy[ib], p.wz[ib]};
      ContactInput c;
      c.inv_inertia_sum = Rolling::has_torque ? p.inv_inertia[ia] + p.inv_inertia[ib] : 0.0;
      const double inv_msum = inv_mi + inv_mj, rm = rsum * inv_msum;
      const double d = std::sqrt(d2);
      const double inv_drm = 1.0 / (d * rm);
      const double inv_d = rm * inv_drm;
      c.n = Vec3{dvec.x * inv_d, dvec.y * inv_d, dvec.z * inv_d};
      c.overlap = rsum - d;
      c.v_rel = dv + cross(wi * ri + wj * rj, c.n);
      c.w_rel = wi - wj;
      const double inv = d * inv_drm;
      c.r_eff = ri * rj * inv_msum * inv;
      c.m_eff = rsum * inv;
      c.d_prev = dvec + dv * dt;
      const ContactOutput out =
          contact_kernel::evaluate<Normal, Tangential, Rolling>(c, pp, hist, dt);
      add_share<Tangential::has_force, Rolling::has_torque>(a, out, p.radius[i],
                                                            first ? 1.0 : -1.0);
      if (first) {
        elastic += out.elastic;
        released += out.spring_loss;
        add_contact(st, c.overlap / (2.0 * std::min(ri, rj)), id_i, out.force);
        if constexpr (Record)
          rec->push_back({id_i, p.id[j], c.overlap, 2.0 * std::min(ri, rj),
                          Vec3{p.x[ia], p.y[ia], p.z[ia]} + c.n * (ri - 0.5 * c.overlap), c.n,
                          out.force, out.torque_roll});
      }
    }
    // Walls: a partner of infinite mass and radius at rest whose normal never turns.
    for (std::uint32_t e = rows.wall_offset[i]; e < rows.wall_offset[i + 1]; ++e) {
      const int f = rows.wall_face[e];
      const int ax = f / 2;
      const bool lo_face = (f % 2 == 0);
      const double xw[3] = {p.x[i], p.y[i], p.z[i]};
      const double ri = p.radius[i];
      const double gap = lo_face ? xw[ax] - box.lo[ax] : box.hi[ax] - xw[ax];
      double* hist = rows.wall_history.data() + static_cast<std::size_t>(e) * hw;
      const PairParams& pp = table.wall(p.species[i], f);
      bool touching = gap < ri;
      if constexpr (contact_kernel::adhesive<Normal>)
        if (!touching && hist[0] != 0.0) touching = gap < ri + Normal::detach_distance(pp, ri);
      if (!touching) {
        if (hw > 0 && loaded(hist)) {
          contact_kernel::add_released_energy<Normal, Tangential, Rolling>(released, hist, pp, ri);
          std::fill_n(hist, hw, 0.0);
        }
        continue;
      }
      ContactInput c;
      c.n = Vec3{};
      (ax == 0 ? c.n.x : ax == 1 ? c.n.y : c.n.z) = lo_face ? -1.0 : 1.0;
      c.fixed_normal = true;
      c.overlap = ri - gap;
      const Vec3 wi{p.wx[i], p.wy[i], p.wz[i]};
      c.v_rel = Vec3{p.vx[i], p.vy[i], p.vz[i]} + cross(wi * ri, c.n);
      c.w_rel = wi;
      c.r_eff = ri;
      c.m_eff = 1.0 / p.inv_mass[i];
      c.inv_inertia_sum = Rolling::has_torque ? p.inv_inertia[i] : 0.0;
      const ContactOutput out =
          contact_kernel::evaluate<Normal, Tangential, Rolling>(c, pp, hist, dt);
      add_share<Tangential::has_force, Rolling::has_torque>(a, out, ri, 1.0);
      elastic += out.elastic;
      released += out.spring_loss;
      add_contact(st, c.overlap / (2.0 * ri), id_i, out.force);
      if constexpr (Record) // the contact point on the wall
        rec->push_back({id_i, -1 - f, c.overlap, 2.0 * ri, Vec3{xw[0], xw[1], xw[2]} + c.n * gap,
                        c.n, out.force, out.torque_roll});
    }
    sums.elastic[i] = elastic;
    sums.released[i] = released;
  };
  OrderedContactStats total;
  if (record) record->clear();
  if (threaded_particles(owned)) {
    // Each particle writes its own sums and its own row's history: any schedule gives the same
    // values; the stats are integers and maxima. The recorded contacts are a set (their users
    // sort them by ids): each thread's are appended in thread order.
    const auto threads = static_cast<std::size_t>(omp_get_max_threads());
    std::vector<OrderedContactStats> per_thread(threads);
    std::vector<std::vector<KeyedContact>> recorded(record ? threads : 0);
#pragma omp parallel
    {
      const auto t = static_cast<std::size_t>(omp_get_thread_num());
      OrderedContactStats& st = per_thread[t];
      std::vector<KeyedContact>* rec = record ? &recorded[t] : nullptr;
#pragma omp for schedule(dynamic, 256)
      for (std::size_t i = 0; i < owned; ++i) row(i, st, rec);
    }
    for (const auto& st : per_thread) join(total, st);
    for (const auto& r : recorded) record->insert(record->end(), r.begin(), r.end());
  } else {
    for (std::size_t i = 0; i < owned; ++i) row(i, total, record);
  }
  return total;
}

} // namespace

OrderedContactStats compute_ordered_contact_forces(const ParticleStore& p, OrderedRows& rows,
                                                   const ContactTable& table, double dt,
                                                   OrderedContactSums& sums,
                                                   std::vector<KeyedContact>* record) {
  using namespace contact_models;
  const Chosen& m = table.models();
  return with_chosen_models<OrderedContactStats>(
      m.normal->index, m.tangential->index, m.rolling->index, [&]<class N, class T, class R>() {
        return record ? compute<N, T, R, true>(p, rows, table, dt, sums, record)
                      : compute<N, T, R, false>(p, rows, table, dt, sums, nullptr);
      });
}

} // namespace fluidem
