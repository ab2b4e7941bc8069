#include "integrate/distributed_soft_sphere.hpp"
#include "noncontact/liquid_bridges.hpp"
#include "noncontact/ordered_noncontact.hpp"
#include "noncontact/pair_forces.hpp"
#include "particles/id_order.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/gravity_axis.hpp"
#include "core/nearest_integer.hpp"
#include "core/parallel.hpp"
#include "integrate/wall_clock.hpp"

namespace fluidem {

DistributedSoftSphere::DistributedSoftSphere(const Communicator& comm,
                                             std::unique_ptr<ContactTable> table,
                                             const BoxGeometry& box, const Settings& settings,
                                             const ParticleStore& all)
    : DistributedSoftSphere(comm, std::move(table), box, settings, all, nullptr) {}

DistributedSoftSphere::DistributedSoftSphere(const Communicator& comm,
                                             std::unique_ptr<ContactTable> table,
                                             const BoxGeometry& box, const Settings& settings,
                                             const DistributedState& state)
    : DistributedSoftSphere(comm, std::move(table), box, settings, state.particles, &state) {}

template <class Self>
auto DistributedSoftSphere::carried_fields(Self& self) {
  using V =
      std::conditional_t<std::is_const_v<Self>, const std::vector<double>, std::vector<double>>;
  const std::size_t nc = self.s_.noncontact ? 1 : 0, tw = self.s_.held_torques ? 3 : 0,
                    aw = static_cast<std::size_t>(self.s_.attached_width),
                    bw = self.s_.liquid_bridge ? 3 : 0;
  // Its dissipated energy, its last contact sums and elastic energy (a build between steps, by
  // rebalance(), keeps them for the next kick), the held gas force, its build position, its
  // non-contact force and potential share, its held torque and attached numbers, its bridges'
  // force.
  return std::array<std::pair<V*, std::size_t>, 10>{{{&self.dissipated_, 1},
                                                     {&self.sums_.elastic, 1},
                                                     {&self.sums_.acc, OrderedContactSums::kAcc},
                                                     {&self.held_, 3},
                                                     {&self.x0_, 3},
                                                     {&self.nc_force_, 3 * nc},
                                                     {&self.nc_potential_, nc},
                                                     {&self.held_torque_, tw},
                                                     {&self.attached_, aw},
                                                     {&self.bridge_force_, bw}}};
}

template <class State>
auto DistributedSoftSphere::state_fields(State& g) {
  using V =
      std::conditional_t<std::is_const_v<State>, const std::vector<double>, std::vector<double>>;
  return std::array<V*, 10>{&g.dissipated, &g.elastic,     &g.contact,  &g.held,        &g.x0,
                            nullptr, // the non-contact force: not kept, recomputed
                            &g.noncontact, &g.held_torque, &g.attached, &g.bridge_force};
}

namespace {

/// The numbers per particle of `fields` (rows of their widths), packed particle by particle.
template <class Fields>
std::size_t packed_width(const Fields& fields) {
  std::size_t w = 0;
  for (const auto& f : fields) w += f.second;
  return w;
}

template <class Fields>
std::vector<double> pack_fields(const Fields& fields, std::size_t n) {
  const std::size_t width = packed_width(fields);
  std::vector<double> out(width * n);
  for (std::size_t i = 0; i < n; ++i) {
    double* c = out.data() + width * i;
    for (const auto& [values, w] : fields) {
      std::copy_n(values->begin() + static_cast<std::ptrdiff_t>(w * i), w, c);
      c += w;
    }
  }
  return out;
}

/// Unpacks `packed` (pack_fields' layout, widths of `fields`) into `to` (one array per field,
/// null: skipped), resized to n particles; particle k of the result is packed particle
/// from[k] (identity when `from` is empty).
template <class Fields, class To>
void unpack_fields(const Fields& fields, const std::vector<double>& packed, const To& to,
                   std::size_t n, const std::vector<std::uint32_t>& from = {}) {
  const std::size_t width = packed_width(fields);
  std::size_t at = 0;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const std::size_t w = fields[f].second;
    if (to[f]) {
      to[f]->resize(w * n);
      for (std::size_t k = 0; k < n; ++k)
        std::copy_n(packed.begin() +
                        static_cast<std::ptrdiff_t>(width * (from.empty() ? k : from[k]) + at),
                    w, to[f]->begin() + static_cast<std::ptrdiff_t>(w * k));
    }
    at += w;
  }
}

} // namespace

DistributedSoftSphere::DistributedSoftSphere(const Communicator& comm,
                                             std::unique_ptr<ContactTable> table,
                                             const BoxGeometry& box, const Settings& settings,
                                             const ParticleStore& all,
                                             const DistributedState* state)
    : comm_(comm), table_(std::move(table)), box_(box), s_(settings),
      map_(settings.cells, comm.size(), gravity_axis(settings.gravity), settings.process_grid) {
  double r_max = 0.0;
  for (const double r : all.radius) r_max = std::max(r_max, r);
  // The ghosts reach as far as the list's cut-off for the largest pair with two skins: the list
  // of a restarted run is built with two (its particles may move half a skin from where the
  // last build saw them, then half a skin from there, before the next build).
  // The non-contact forces' own rows reach farther (their range); the ghosts cover both.
  const double reach = table_->attached_reach(r_max);
  // So do the liquid bridges' (the longest rupture distance).
  const double nc_reach = s_.noncontact ? noncontact_reach(*s_.noncontact, all) : 0.0;
  const double bridge_reach =
      s_.liquid_bridge ? longest_rupture_distance(*s_.liquid_bridge, s_.liquid_fraction, all) : 0.0;
  exchange_ = std::make_unique<ParticleExchange>(
      comm_, map_, 2.0 * r_max + std::max({reach, nc_reach, bridge_reach}) + 2.0 * s_.skin);
  rows_ = std::make_unique<OrderedRows>(box_, table_->history_width(), reach);
  if (s_.noncontact) nc_rows_ = std::make_unique<OrderedRows>(box_, 0, nc_reach);
  if (s_.liquid_bridge)
    bridges_ = std::make_unique<OrderedLiquidBridges>(box_, *s_.liquid_bridge, s_.liquid_fraction,
                                                      bridge_reach);
  // Each rank keeps the particles whose centres its cells hold, with what they carry.
  std::vector<std::uint32_t> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (map_.owner(all.x[i], all.y[i], all.z[i]) == comm_.rank())
      mine.push_back(static_cast<std::uint32_t>(i));
  p_ = all;
  p_.permute(mine);
  p_.resize(mine.size());
  owned_ = p_.size();
  total_ = static_cast<std::int64_t>(all.size());
  KeptHistory kept, kept_bridges;
  kept.width = rows_->history_width();
  kept.offset.assign(1, 0);
  kept_bridges.width = 1;
  kept_bridges.offset.assign(1, 0);
  dissipated_.assign(owned_, 0.0);
  bridge_force_.assign(bridges_ ? 3 * owned_ : 0, 0.0);
  held_.assign(3 * owned_, 0.0);
  const auto aw = static_cast<std::size_t>(s_.attached_width);
  held_torque_.assign(s_.held_torques ? 3 * owned_ : 0, 0.0);
  attached_.assign(aw * owned_, 0.0);
  x0_.resize(3 * owned_);
  if (state) {
    sums_.acc.resize(OrderedContactSums::kAcc * owned_);
    sums_.elastic.resize(owned_);
    sums_.released.assign(owned_, 0.0);
    // What travels with each particle, from the state's arrays (those it keeps: a state without
    // held forces, torques or attached numbers leaves them 0).
    const auto fields = carried_fields(*this);
    const auto from = state_fields(*state);
    for (std::size_t f = 0; f < fields.size(); ++f) {
      const std::size_t w = fields[f].second;
      if (!from[f] || from[f]->empty() || w == 0) continue;
      std::vector<double>& to = *fields[f].first;
      to.resize(w * owned_);
      for (std::size_t k = 0; k < owned_; ++k)
        std::copy_n(from[f]->begin() + static_cast<std::ptrdiff_t>(w * mine[k]), w,
                    to.begin() + static_cast<std::ptrdiff_t>(w * k));
    }
    // The own particles' entries of the state's histories (none kept, as gather() without
    // histories or a run without bridges leaves them: none).
    const auto select = [&](const KeptHistory& h, KeptHistory& to) {
      if (!h.offset.empty() && h.offset.size() != all.size() + 1)
        throw std::logic_error("DistributedSoftSphere: a state's histories are not of its " +
                               std::to_string(all.size()) + " particles");
      const auto hw = static_cast<std::size_t>(to.width);
      for (std::size_t k = 0; k < owned_; ++k) {
        const std::size_t i = mine[k];
        if (!h.offset.empty())
          for (std::uint32_t m = h.offset[i]; m < h.offset[i + 1]; ++m) {
            to.key.push_back(h.key[m]);
            to.values.insert(to.values.end(),
                             h.values.begin() + static_cast<std::ptrdiff_t>(m * hw),
                             h.values.begin() + static_cast<std::ptrdiff_t>((m + 1) * hw));
          }
        to.offset.push_back(static_cast<std::uint32_t>(to.key.size()));
      }
    };
    select(state->history, kept);
    select(state->bridges, kept_bridges);
    builds_ = state->builds;
  } else {
    kept.offset.assign(owned_ + 1, 0);
    kept_bridges.offset.assign(owned_ + 1, 0);
    builds_ = 1; // the first build, below
  }
  // The first list. A restarted run's: the checkpoint holds every loaded history, and the rows'
  // order does not depend on when they were built; its next build comes when the uninterrupted
  // run's would (from the build positions of the checkpoint), so this list holds the pairs
  // within two skins.
  exchange_->fill_ghosts(p_);
  rows_->build(p_, owned_, state ? 2.0 * s_.skin : s_.skin, kept);
  if (nc_rows_) { // (a restarted run's: recomputed from the positions, the same bits)
    nc_rows_->build(p_, owned_, state ? 2.0 * s_.skin : s_.skin, {});
    compute_noncontact();
  }
  if (bridges_) // (a restarted run's forces: the state's, those of its last step)
    bridges_->rows().build(p_, owned_, state ? 2.0 * s_.skin : s_.skin, kept_bridges);
  if (!state)
    for (std::size_t k = 0; k < owned_; ++k)
      x0_[3 * k] = p_.x[k], x0_[3 * k + 1] = p_.y[k], x0_[3 * k + 2] = p_.z[k];
  if (!state) stats_ = compute_ordered_contact_forces(p_, *rows_, *table_, s_.dt, sums_);
  if (!state && bridges_) compute_bridges();
  observed_stats_.max_overlap_ratio = comm_.max(stats_.max_overlap_ratio);
}

std::size_t DistributedSoftSphere::bytes() const {
  // The rank's store (own particles and ghosts), rows, histories and per-particle sums.
  return p_.bytes() +
         (rows_->partner.capacity() + rows_->offset.capacity() + rows_->wall_offset.capacity()) *
             sizeof(std::uint32_t) +
         (rows_->history.capacity() + rows_->wall_history.capacity() + sums_.acc.capacity() +
          sums_.elastic.capacity() + sums_.released.capacity() + x0_.capacity() +
          dissipated_.capacity() + held_.capacity() + held_torque_.capacity() +
          attached_.capacity() + bridge_force_.capacity()) *
             sizeof(double) +
         (bridges_ ? bridges_->rows().partner.capacity() * sizeof(std::uint32_t) +
                         bridges_->rows().history.capacity() * sizeof(double)
                   : 0);
}

namespace {
constexpr std::array<double, 3> kNoForce{};
} // namespace

void DistributedSoftSphere::compute_noncontact() {
  ordered_noncontact_forces(*s_.noncontact, *nc_rows_, p_, nc_force_, nc_potential_);
}

void DistributedSoftSphere::compute_bridges() {
  bridges_->compute(
      p_, [&](std::vector<double>& v) { exchange_->update_ghost_values(v, owned_); },
      bridge_force_);
}

std::vector<KeptHistory> DistributedSoftSphere::keep_histories() const {
  std::vector<KeptHistory> kept{rows_->keep(p_)};
  if (bridges_) kept.push_back(bridges_->rows().keep(p_));
  return kept;
}

void DistributedSoftSphere::kick() {
  // Velocity Verlet's half kick with the last forces: dv = (F/m + g + a_body(x)) dt/2,
  // dw = T/I dt/2; a fixed particle (1/m = 0) gets no acceleration at all.
  const double h = 0.5 * s_.dt;
  const auto& g = s_.gravity;
  parallel_for(owned_, threaded_particles(owned_), [&](std::size_t i) {
    const double* f = sums_.acc.data() + OrderedContactSums::kAcc * i;
    const double* fh = held_.data() + 3 * i;
    const double* fn = nc_rows_ ? nc_force_.data() + 3 * i : kNoForce.data();
    const double im = p_.inv_mass[i], ii = p_.inv_inertia[i];
    std::array<double, 3> a = g;
    if (s_.body) { // at the particle's position now: x^n in the first kick, x^{n+1} in the second
      const auto b = body_acceleration(*s_.body, p_.x[i], p_.y[i], p_.z[i]);
      a[0] += b[0], a[1] += b[1], a[2] += b[2];
    }
    if (im == 0.0) a = {0.0, 0.0, 0.0};
    std::array<double, 3> force{f[0] + fh[0] + fn[0], f[1] + fh[1] + fn[1], f[2] + fh[2] + fn[2]};
    if (bridges_) {
      const double* fb = bridge_force_.data() + 3 * i;
      force[0] += fb[0], force[1] += fb[1], force[2] += fb[2];
    }
    p_.vx[i] += h * (force[0] * im + a[0]);
    p_.vy[i] += h * (force[1] * im + a[1]);
    p_.vz[i] += h * (force[2] * im + a[2]);
    if (s_.held_torques) {
      const double* th = held_torque_.data() + 3 * i;
      p_.wx[i] += h * (f[3] + th[0]) * ii;
      p_.wy[i] += h * (f[4] + th[1]) * ii;
      p_.wz[i] += h * (f[5] + th[2]) * ii;
    } else {
      p_.wx[i] += h * f[3] * ii;
      p_.wy[i] += h * f[4] * ii;
      p_.wz[i] += h * f[5] * ii;
    }
  });
}

void DistributedSoftSphere::step() {
  auto t0 = WallClock::now();
  kick();
  // Drift; the displacement since the build decides the next build, and one beyond the halo
  // stops the run (the ghosts would no longer hold every partner).
  const double dt = s_.dt;
  const double far2 = 0.25 * s_.skin * s_.skin;
  const double halo2 = exchange_->halo() * exchange_->halo();
  double moved_far = 0.0, too_far = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < owned_; ++i) {
    double x[3] = {p_.x[i] + dt * p_.vx[i], p_.y[i] + dt * p_.vy[i], p_.z[i] + dt * p_.vz[i]};
    for (int a = 0; a < 3; ++a)
      if (box_.periodic[a]) x[a] = wrapped(x[a], box_.lo[a], box_.length(a));
    p_.x[i] = x[0], p_.y[i] = x[1], p_.z[i] = x[2];
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double d = rows_->min_image(x[a] - x0_[3 * i + static_cast<std::size_t>(a)], a);
      d2 += d * d;
    }
    if (d2 > far2) moved_far = 1.0;
    if (d2 > halo2) too_far = std::min(too_far, static_cast<double>(p_.id[i]));
  }
  const double first_too_far = comm_.min(too_far);
  if (std::isfinite(first_too_far))
    throw InstabilityError("particle " + std::to_string(static_cast<std::int64_t>(first_too_far)) +
                           " moved farther than the halo of the ranks' boxes (" +
                           std::to_string(exchange_->halo()) +
                           " m) within one neighbour list's life: the run is unstable (reduce "
                           "the time step)");
  seconds_.integration += seconds_since(t0);
  t0 = WallClock::now();
  if (comm_.max(moved_far) > 0.0)
    rebuild();
  else
    exchange_->update_ghosts(p_, owned_);
  seconds_.neighbour += seconds_since(t0);
  t0 = WallClock::now();
  contacts_.clear();
  stats_ = compute_ordered_contact_forces(p_, *rows_, *table_, dt, sums_,
                                          record_ ? &contacts_ : nullptr);
  if (nc_rows_) compute_noncontact();
  if (bridges_) compute_bridges();
  observed_stats_.max_overlap_ratio = comm_.max(stats_.max_overlap_ratio);
  seconds_.contacts += seconds_since(t0);
  t0 = WallClock::now();
  kick();
  // The work of the non-conservative contact forces with the full-step velocities, and the
  // spring energy released by contacts that ended, per particle.
  for (std::size_t i = 0; i < owned_; ++i) {
    const double* f = sums_.acc.data() + OrderedContactSums::kAcc * i;
    const double w = (f[6] * p_.vx[i] + f[7] * p_.vy[i] + f[8] * p_.vz[i]) +
                     (f[9] * p_.wx[i] + f[10] * p_.wy[i] + f[11] * p_.wz[i]);
    dissipated_[i] += -w * dt;
    dissipated_[i] += sums_.released[i];
  }
  // The liquid bridges' work with the full-step velocities (a fixed particle does none): their
  // capillary force loses the bridge energy over a form-rupture cycle, their viscous force
  // dissipates (integrate/liquid_bridge_source.hpp).
  if (bridges_)
    for (std::size_t i = 0; i < owned_; ++i) {
      if (p_.inv_mass[i] == 0.0) continue;
      const double* fb = bridge_force_.data() + 3 * i;
      dissipated_[i] += -dt * (fb[0] * p_.vx[i] + fb[1] * p_.vy[i] + fb[2] * p_.vz[i]);
    }
  seconds_.integration += seconds_since(t0);
}

void DistributedSoftSphere::advance(long steps) {
  for (long k = 0; k < steps; ++k) step();
}

void DistributedSoftSphere::rebalance(bool measured) {
  // Each rank's own particles' cost per cell layer of each axis, summed on the root in rank
  // order; the root places the cuts and every rank takes them.
  const auto& g = map_.grid();
  const double seconds = seconds_.contacts - balance_seconds0_;
  balance_seconds0_ = seconds_.contacts;
  double work = 0.0;
  for (std::size_t i = 0; i < owned_; ++i)
    work += 1.0 + static_cast<double>(rows_->offset[i + 1] - rows_->offset[i]);
  const double scale = measured && work > 0.0 && seconds > 0.0 ? seconds / work : 1.0;
  std::vector<double> cost;
  for (int a = 0; a < 3; ++a) {
    if (map_.process_grid()[static_cast<std::size_t>(a)] < 2) continue;
    const std::size_t at = cost.size();
    cost.resize(at + static_cast<std::size_t>(g.cells[static_cast<std::size_t>(a)]), 0.0);
    const std::vector<double>* x = a == 0 ? &p_.x : a == 1 ? &p_.y : &p_.z;
    for (std::size_t i = 0; i < owned_; ++i)
      cost[at + static_cast<std::size_t>(map_.cell_of(a, (*x)[i]))] +=
          scale * (1.0 + static_cast<double>(rows_->offset[i + 1] - rows_->offset[i]));
  }
  const auto parts = comm_.gather(std::span<const char>(reinterpret_cast<const char*>(cost.data()),
                                                        cost.size() * sizeof(double)));
  std::vector<int> cuts;
  if (comm_.root()) {
    std::vector<double> total(cost.size(), 0.0);
    for (const auto& b : parts)
      for (std::size_t k = 0; k < total.size(); ++k) {
        double v;
        std::memcpy(&v, b.data() + k * sizeof(double), sizeof(double));
        total[k] += v;
      }
    std::size_t at = 0;
    for (int a = 0; a < 3; ++a) {
      const int n = map_.process_grid()[static_cast<std::size_t>(a)];
      if (n < 2) continue;
      const auto cells = static_cast<std::size_t>(g.cells[static_cast<std::size_t>(a)]);
      const std::vector<double> layer(total.begin() + static_cast<std::ptrdiff_t>(at),
                                      total.begin() + static_cast<std::ptrdiff_t>(at + cells));
      const std::vector<int> c = Decomposition::balanced_cuts(layer, n, 1);
      cuts.insert(cuts.end(), c.begin(), c.end());
      at += cells;
    }
  }
  std::vector<char> bytes(reinterpret_cast<const char*>(cuts.data()),
                          reinterpret_cast<const char*>(cuts.data() + cuts.size()));
  comm_.broadcast(bytes);
  cuts.resize(bytes.size() / sizeof(int));
  std::memcpy(cuts.data(), bytes.data(), bytes.size());
  std::size_t at = 0;
  for (int a = 0; a < 3; ++a) {
    const int n = map_.process_grid()[static_cast<std::size_t>(a)];
    if (n < 2) continue;
    map_.set_cuts(a, std::vector<int>(cuts.begin() + static_cast<std::ptrdiff_t>(at),
                                      cuts.begin() + static_cast<std::ptrdiff_t>(at) + n + 1));
    at += static_cast<std::size_t>(n) + 1;
  }
  sent_before_[0] += exchange_->bytes_sent(), sent_before_[1] += exchange_->messages_sent();
  exchange_ = std::make_unique<ParticleExchange>(comm_, map_, exchange_->halo());
  ++rebalances_;
  // The particles to their new owners. Planes that moved far can give a particle to a rank
  // whose box is not next to its old owner's: this one migration may go to every rank.
  ParticleExchange anywhere(comm_, map_, std::numeric_limits<double>::infinity());
  rebuild(&anywhere);
  sent_before_[0] += anywhere.bytes_sent(), sent_before_[1] += anywhere.messages_sent();
}

void DistributedSoftSphere::rebuild(ParticleExchange* migration) {
  // The cut planes move to balance the measured cost every balance_interval builds, before the
  // particles move to their owners (rebalance() calls this again with the new cuts).
  if (s_.balance_interval > 0 && builds_ > 0 && builds_ % s_.balance_interval == 0 &&
      comm_.size() > 1 && rebalances_ < builds_ / s_.balance_interval) {
    rebalance(true);
    return;
  }
  // The own particles' histories leave the rows keyed by partner id; the ghosts are dropped.
  std::vector<KeptHistory> kept = keep_histories();
  std::vector<KeptHistory*> travelling;
  for (KeptHistory& h : kept) travelling.push_back(&h);
  p_.resize(owned_);
  // What travels with each particle (carried_fields).
  const auto fields = carried_fields(*this);
  std::vector<double> carried = pack_fields(fields, owned_);
  const std::vector<ParticleTooFar> lost =
      (migration ? *migration : *exchange_)
          .migrate(p_, travelling, carried, static_cast<int>(packed_width(fields)));
  std::array<std::vector<double>*, std::tuple_size_v<decltype(fields)>> to{};
  for (std::size_t f = 0; f < fields.size(); ++f) to[f] = fields[f].first;
  unpack_fields(fields, carried, to, p_.size());
  const double first_lost = comm_.min(lost.empty() ? std::numeric_limits<double>::infinity()
                                                   : static_cast<double>(lost.front().id));
  if (std::isfinite(first_lost))
    throw InstabilityError("particle " + std::to_string(static_cast<std::int64_t>(first_lost)) +
                           " left the ranks next to its own in one neighbour list's life: the run "
                           "is unstable (reduce the time step)");
  owned_ = p_.size();
  const std::int64_t count = comm_.sum(static_cast<std::int64_t>(owned_));
  if (count != total_)
    throw InstabilityError("the ranks hold " + std::to_string(count) + " particles, the run has " +
                           std::to_string(total_) + ": a particle was lost or duplicated");
  exchange_->fill_ghosts(p_);
  rows_->build(p_, owned_, s_.skin, kept[0]);
  if (nc_rows_) nc_rows_->build(p_, owned_, s_.skin, {});
  if (bridges_) bridges_->rows().build(p_, owned_, s_.skin, kept[1]);
  x0_.resize(3 * owned_);
  for (std::size_t i = 0; i < owned_; ++i)
    x0_[3 * i] = p_.x[i], x0_[3 * i + 1] = p_.y[i], x0_[3 * i + 2] = p_.z[i];
  ++builds_;
}

DistributedState DistributedSoftSphere::gather(bool with_history) const {
  // Per particle: what travels with it (carried_fields); then (with_history) its entries.
  const auto fields = carried_fields(*this);
  const auto kExtra = packed_width(fields);
  const std::vector<double> extra = pack_fields(fields, owned_);
  const auto parts = comm_.gather(pack_particles(p_, owned_, extra, static_cast<int>(kExtra)));
  std::vector<std::vector<char>> history_parts, bridge_parts;
  if (with_history) {
    history_parts = comm_.gather(pack_history(rows_->keep(p_)));
    if (bridges_) bridge_parts = comm_.gather(pack_history(bridges_->rows().keep(p_)));
  }
  DistributedState g;
  g.builds = builds_;
  if (!comm_.root()) return g;
  ParticleStore& p = g.particles;
  std::vector<double> all_extra;
  for (const auto& b : parts) unpack_particles(b, p, all_extra, static_cast<int>(kExtra));
  KeptHistory all_kept;
  all_kept.width = rows_->history_width();
  all_kept.offset.assign(1, 0);
  for (const auto& b : history_parts) unpack_history(b, all_kept);
  const std::vector<std::uint32_t> order = id_order(p);
  p.permute(order);
  const std::size_t n = order.size();
  unpack_fields(fields, all_extra, state_fields(g), n, order);
  if (g.noncontact.empty()) g.noncontact.assign(n, 0.0); // without non-contact forces: 0 each
  if (with_history) g.history = reorder(all_kept, order);
  if (with_history && bridges_) {
    KeptHistory all_bridges;
    all_bridges.width = 1;
    all_bridges.offset.assign(1, 0);
    for (const auto& b : bridge_parts) unpack_history(b, all_bridges);
    g.bridges = reorder(all_bridges, order);
  }
  return g;
}

std::vector<KeyedContact> DistributedSoftSphere::gather_contacts() const {
  static_assert(std::is_trivially_copyable_v<KeyedContact>);
  const auto parts = comm_.gather(std::span<const char>(
      reinterpret_cast<const char*>(contacts_.data()), contacts_.size() * sizeof(KeyedContact)));
  std::vector<KeyedContact> all;
  for (const auto& b : parts) {
    const std::size_t at = all.size();
    all.resize(at + b.size() / sizeof(KeyedContact));
    std::memcpy(all.data() + at, b.data(), b.size());
  }
  return all;
}

ParticleStore
DistributedSoftSphere::gather_where(const std::function<bool(const Vec3&)>& keep) const {
  std::vector<std::uint32_t> chosen;
  for (std::size_t i = 0; i < owned_; ++i)
    if (keep(p_.position(i))) chosen.push_back(static_cast<std::uint32_t>(i));
  ParticleStore mine;
  mine.resize(chosen.size());
  std::vector<const void*> from;
  p_.for_each_array([&](const auto& a) { from.push_back(&a); });
  std::size_t k = 0;
  mine.for_each_array([&](auto& a) {
    using A = std::remove_reference_t<decltype(a)>;
    const A& src = *static_cast<const A*>(from[k++]);
    for (std::size_t m = 0; m < chosen.size(); ++m) a[m] = src[chosen[m]];
  });
  const auto parts = comm_.gather(pack_particles(mine, mine.size(), {}, 0));
  ParticleStore all;
  std::vector<double> no_extra;
  for (const auto& b : parts) unpack_particles(b, all, no_extra, 0);
  all.permute(id_order(all));
  return all;
}

void DistributedSoftSphere::own_particles(ParticleStore& out) const {
  out.resize(owned_);
  std::vector<const void*> from;
  p_.for_each_array([&](const auto& a) { from.push_back(&a); });
  std::size_t k = 0;
  out.for_each_array([&](auto& a) {
    using A = std::remove_reference_t<decltype(a)>;
    const A& src = *static_cast<const A*>(from[k++]);
    std::copy_n(src.begin(), owned_, a.begin());
  });
}

void DistributedSoftSphere::hold_own_forces(const std::array<const double*, 3>& f) {
  for (std::size_t i = 0; i < owned_; ++i)
    for (std::size_t a = 0; a < 3; ++a) held_[3 * i + a] = f[a][i];
}

std::vector<std::size_t> DistributedSoftSphere::index_in(const ParticleStore& all,
                                                         const char* what) const {
  std::vector<std::size_t> index(owned_);
  for (std::size_t i = 0; i < owned_; ++i) {
    const auto it = std::lower_bound(all.id.begin(), all.id.end(), p_.id[i]);
    if (it == all.id.end() || *it != p_.id[i])
      throw std::logic_error(std::string("DistributedSoftSphere::") + what + ": particle " +
                             std::to_string(p_.id[i]) + " is not among all particles");
    index[i] = static_cast<std::size_t>(it - all.id.begin());
  }
  return index;
}

void DistributedSoftSphere::hold_forces(const ParticleStore& all,
                                        const std::array<const double*, 3>& f) {
  const std::vector<std::size_t> index = index_in(all, "hold_forces");
  for (std::size_t i = 0; i < owned_; ++i)
    for (std::size_t a = 0; a < 3; ++a) held_[3 * i + a] = f[a][index[i]];
}

void DistributedSoftSphere::hold_own_torques(const std::array<const double*, 3>& t) {
  if (!s_.held_torques) throw std::logic_error("DistributedSoftSphere: no held torques");
  for (std::size_t i = 0; i < owned_; ++i)
    for (std::size_t a = 0; a < 3; ++a) held_torque_[3 * i + a] = t[a][i];
}

void DistributedSoftSphere::hold_torques(const ParticleStore& all,
                                         const std::array<const double*, 3>& t) {
  if (!s_.held_torques) throw std::logic_error("DistributedSoftSphere: no held torques");
  const std::vector<std::size_t> index = index_in(all, "hold_torques");
  for (std::size_t i = 0; i < owned_; ++i)
    for (std::size_t a = 0; a < 3; ++a) held_torque_[3 * i + a] = t[a][index[i]];
}

void DistributedSoftSphere::set_attached(const ParticleStore& all, std::span<const double> values) {
  const auto aw = static_cast<std::size_t>(s_.attached_width);
  if (values.size() != aw * all.size())
    throw std::logic_error("DistributedSoftSphere::set_attached: " + std::to_string(values.size()) +
                           " numbers for " + std::to_string(all.size()) + " particles of width " +
                           std::to_string(aw));
  const std::vector<std::size_t> index = index_in(all, "set_attached");
  for (std::size_t i = 0; i < owned_; ++i)
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(aw * index[i]), aw,
                attached_.begin() + static_cast<std::ptrdiff_t>(aw * i));
}

void DistributedSoftSphere::add_inertia(const std::function<double(double)>& added) {
  for (std::size_t i = 0; i < p_.size(); ++i) // own particles and ghosts alike
    if (p_.inv_mass[i] > 0.0) p_.inv_mass[i] = 1.0 / (p_.mass[i] + added(2.0 * p_.radius[i]));
}

void DistributedSoftSphere::observe(ParticleStore& all) {
  DistributedState g = gather();
  const Totals t = totals_of(g);
  observed_dissipated_ = t.dissipated;
  observed_noncontact_ = t.noncontact;
  ContactStats& st = observed_stats_;
  st.n_contacts = t.contacts;
  st.elastic_energy = t.elastic;
  st.spring_losses = 0.0; // in each particle's dissipated energy already
  st.max_overlap_ratio = t.max_overlap_ratio;
  st.max_force2 = comm_.max(stats_.max_force2);
  // The deepest contact's lower id: the lowest of the ranks that saw the deepest overlap.
  const double mine = stats_.max_overlap_ratio == t.max_overlap_ratio && stats_.deepest_id >= 0
                          ? static_cast<double>(stats_.deepest_id)
                          : std::numeric_limits<double>::infinity();
  const double deepest = comm_.min(mine);
  st.max_overlap_particle = std::isfinite(deepest) ? static_cast<long>(deepest) : -1;
  all = std::move(g.particles);
}

DistributedSoftSphere::Totals DistributedSoftSphere::totals() const {
  return totals_of(gather());
}

DistributedSoftSphere::Totals DistributedSoftSphere::totals_of(const DistributedState& g) const {
  std::vector<double> t(6, 0.0);
  if (comm_.root()) {
    const ParticleStore& p = g.particles;
    const auto& gr = s_.gravity;
    for (std::size_t i = 0; i < p.size(); ++i) {
      t[0] += 0.5 * p.mass[i] * (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] + p.vz[i] * p.vz[i]);
      const double inertia = 0.4 * p.mass[i] * p.radius[i] * p.radius[i];
      t[1] += 0.5 * inertia * (p.wx[i] * p.wx[i] + p.wy[i] * p.wy[i] + p.wz[i] * p.wz[i]);
      t[2] += -p.mass[i] * (gr[0] * p.x[i] + gr[1] * p.y[i] + gr[2] * p.z[i]);
      t[3] += g.elastic[i];
      t[4] += g.dissipated[i];
      t[5] += g.noncontact[i];
    }
  }
  std::vector<char> bytes(reinterpret_cast<const char*>(t.data()),
                          reinterpret_cast<const char*>(t.data() + t.size()));
  comm_.broadcast(bytes);
  std::memcpy(t.data(), bytes.data(), t.size() * sizeof(double));
  Totals out;
  out.kinetic = t[0], out.rotational = t[1], out.potential = t[2];
  out.elastic = t[3], out.dissipated = t[4], out.noncontact = t[5];
  out.contacts = comm_.sum(stats_.contacts);
  out.particles = comm_.sum(static_cast<std::int64_t>(owned_));
  out.bridges = bridges_ ? comm_.sum(bridges_->bridges(p_)) : 0;
  out.max_overlap_ratio = comm_.max(stats_.max_overlap_ratio);
  return out;
}

} // namespace fluidem
