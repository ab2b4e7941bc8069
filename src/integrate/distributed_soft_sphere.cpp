#include "integrate/distributed_soft_sphere.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include "core/error.hpp"
#include "core/nearest_integer.hpp"
#include "core/parallel.hpp"

namespace fluidem {

namespace {

int gravity_axis(const std::array<double, 3>& g) {
  int axis = 2;
  for (int a = 0; a < 3; ++a)
    if (std::abs(g[static_cast<std::size_t>(a)]) > std::abs(g[static_cast<std::size_t>(axis)]))
      axis = a;
  return axis;
}

} // namespace

DistributedSoftSphere::DistributedSoftSphere(const Communicator& comm,
                                             std::unique_ptr<ContactTable> table,
                                             const BoxGeometry& box, const Settings& settings,
                                             const ParticleStore& all)
    : comm_(comm), table_(std::move(table)), box_(box), s_(settings),
      map_(settings.cells, comm.size(), gravity_axis(settings.gravity), settings.process_grid) {
  double r_max = 0.0;
  for (const double r : all.radius) r_max = std::max(r_max, r);
  // The ghosts reach as far as the list's cut-off for the largest pair.
  const double halo = 2.0 * r_max + table_->attached_reach(r_max) + s_.skin;
  exchange_ = std::make_unique<ParticleExchange>(comm_, map_, halo);
  rows_ =
      std::make_unique<OrderedRows>(box_, table_->history_width(), table_->attached_reach(r_max));
  // Each rank keeps the particles whose centres its cells hold.
  std::vector<std::uint32_t> mine;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (map_.owner(all.x[i], all.y[i], all.z[i]) == comm_.rank())
      mine.push_back(static_cast<std::uint32_t>(i));
  p_ = all;
  p_.permute(mine);
  p_.resize(mine.size());
  owned_ = p_.size();
  dissipated_.assign(owned_, 0.0);
  total_ = static_cast<std::int64_t>(all.size());
  rebuild();
  stats_ = compute_ordered_contact_forces(p_, *rows_, *table_, s_.dt, sums_);
}

void DistributedSoftSphere::kick() {
  // Velocity Verlet's half kick with the last forces: dv = (F/m + g) dt/2, dw = T/I dt/2; a fixed
  // particle (1/m = 0) gets no acceleration at all.
  const double h = 0.5 * s_.dt;
  const auto& g = s_.gravity;
  parallel_for(owned_, threaded_particles(owned_), [&](std::size_t i) {
    const double* f = sums_.acc.data() + OrderedContactSums::kAcc * i;
    const double im = p_.inv_mass[i], ii = p_.inv_inertia[i];
    const std::array<double, 3> a = im == 0.0 ? std::array<double, 3>{} : g;
    p_.vx[i] += h * (f[0] * im + a[0]);
    p_.vy[i] += h * (f[1] * im + a[1]);
    p_.vz[i] += h * (f[2] * im + a[2]);
    p_.wx[i] += h * f[3] * ii;
    p_.wy[i] += h * f[4] * ii;
    p_.wz[i] += h * f[5] * ii;
  });
}

void DistributedSoftSphere::step() {
  kick();
  // Drift; the displacement since the build decides the next build, and one beyond the halo
  // stops the run (the ghosts would no longer hold every partner).
  const double dt = s_.dt;
  const double far2 = 0.25 * rows_->skin() * rows_->skin();
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
  if (comm_.max(moved_far) > 0.0)
    rebuild();
  else
    exchange_->update_ghosts(p_, owned_);
  stats_ = compute_ordered_contact_forces(p_, *rows_, *table_, dt, sums_);
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
}

void DistributedSoftSphere::advance(long steps) {
  for (long k = 0; k < steps; ++k) step();
}

void DistributedSoftSphere::rebuild() {
  // The own particles' histories leave the rows keyed by partner id; the ghosts are dropped.
  KeptHistory kept = builds_ > 0 ? rows_->keep(p_) : KeptHistory{};
  if (builds_ == 0) {
    kept.width = rows_->history_width();
    kept.offset.assign(owned_ + 1, 0);
  }
  p_.resize(owned_);
  const std::vector<ParticleTooFar> lost = exchange_->migrate(p_, kept, dissipated_, 1);
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
  rows_->build(p_, owned_, s_.skin, kept);
  x0_.resize(3 * owned_);
  for (std::size_t i = 0; i < owned_; ++i)
    x0_[3 * i] = p_.x[i], x0_[3 * i + 1] = p_.y[i], x0_[3 * i + 2] = p_.z[i];
  ++builds_;
}

DistributedSoftSphere::Gathered DistributedSoftSphere::gather() const {
  std::vector<double> extra(2 * owned_);
  for (std::size_t i = 0; i < owned_; ++i)
    extra[2 * i] = dissipated_[i], extra[2 * i + 1] = sums_.elastic[i];
  const std::vector<char> mine = pack_particles(p_, owned_, extra, 2);
  const auto parts = comm_.gather(mine);
  Gathered g;
  if (!comm_.root()) return g;
  std::vector<double> all_extra;
  for (const auto& b : parts) unpack_particles(b, g.particles, all_extra, 2);
  std::vector<std::uint32_t> order(g.particles.size());
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return g.particles.id[a] < g.particles.id[b];
  });
  g.particles.permute(order);
  g.dissipated.resize(order.size());
  g.elastic.resize(order.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    g.dissipated[k] = all_extra[2 * order[k]], g.elastic[k] = all_extra[2 * order[k] + 1];
  return g;
}

DistributedSoftSphere::Totals DistributedSoftSphere::totals() const {
  const Gathered g = gather();
  std::vector<double> t(8, 0.0);
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
    }
  }
  std::vector<char> bytes(reinterpret_cast<const char*>(t.data()),
                          reinterpret_cast<const char*>(t.data() + t.size()));
  comm_.broadcast(bytes);
  std::copy_n(reinterpret_cast<const double*>(bytes.data()), t.size(), t.data());
  Totals out;
  out.kinetic = t[0], out.rotational = t[1], out.potential = t[2];
  out.elastic = t[3], out.dissipated = t[4];
  out.contacts = comm_.sum(stats_.contacts);
  out.particles = comm_.sum(static_cast<std::int64_t>(owned_));
  out.max_overlap_ratio = comm_.max(stats_.max_overlap_ratio);
  return out;
}

} // namespace fluidem
