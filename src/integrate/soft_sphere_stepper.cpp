#include "integrate/soft_sphere_stepper.hpp"
#include "integrate/wall_clock.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/parallel.hpp"
#include "neighbour/spatial_order.hpp"

namespace fluidem {

namespace {

/// Steps fold (SoftSphereStepper::step) only in beds with at least this many neighbour-list
/// pairs per particle: there the contact loop streams every particle through the cache anyway
/// and the fold saves the separate pass; in sparser beds the fold's pass, in slab order, ran
/// slower than the separate one in index order (bench/RESULTS.md, "folded step").
constexpr double kFoldPairsPerParticle = 3.0;
double fold_pairs_threshold = kFoldPairsPerParticle;

} // namespace

double SoftSphereStepper::fold_pairs_per_particle() {
  return fold_pairs_threshold;
}

void SoftSphereStepper::set_fold_pairs_per_particle(double pairs) {
  fold_pairs_threshold = pairs;
}

SoftSphereStepper::SoftSphereStepper(std::unique_ptr<ContactTable> table, const BoxGeometry& box,
                                     const Settings& settings, ParticleStore& p,
                                     ForceSources& forces, ContactRecord* record)
    : p_(p), forces_(forces), record_(record), table_(std::move(table)), dt_(settings.dt),
      sort_interval_(settings.sort_interval) {
  for (const double im : p_.inv_mass) max_inv_mass_ = std::max(max_inv_mass_, im);
  // An adhesive contact (JKR) holds in tension down to an overlap of -delta_c: the list holds
  // every pair out to that gap (its reach).
  double r_max = 0.5 * settings.max_diameter;
  for (const double r : p_.radius) r_max = std::max(r_max, r);
  nl_ = std::make_unique<NeighbourList>(box, settings.skin, contact_history_width(*table_),
                                        table_->attached_reach(r_max));
  // neighbour.skin = "auto": each build chooses its skin from the particles' speeds, for lists
  // that last auto_skin_steps steps, between the given skin and the largest diameter.
  if (settings.auto_skin)
    nl_->set_auto_skin({dt_, settings.auto_skin_steps, settings.skin, settings.max_diameter});
  if (settings.sort_first)
    sort_and_rebuild(); // the first build, so no history to carry over
  else
    nl_->build(p_);
  compute_forces();
}

std::size_t SoftSphereStepper::bytes() const {
  return nl_->bytes() + nc_.bytes();
}

void SoftSphereStepper::compute_forces(ScratchState scratch) {
  const auto t0 = WallClock::now();
  stats_ = compute_contact_forces(p_, *nl_, *table_, dt_, nc_, record_, scratch);
  t_contacts_ += seconds_since(t0);
  e_dsp_ += stats_.spring_losses;
}

/// The half kick of a particle with the last force evaluation, dv = ((F + F_s)/m + g + a(x))
/// dt/2, dw = (T + T_s)/I dt/2; F_s, T_s the sources' summed force and torque, a(x) the body force
/// field at the particle's current position (velocity Verlet with a position-dependent force: x^n
/// in the first half kick, x^{n+1} in the second). The contact forces and torques are in nc_: a
/// step's first kick reads the previous step's, the second this step's.
struct SoftSphereStepper::Kick {
  explicit Kick(const SoftSphereStepper& s)
      : contact(s.nc_.acc.data()), gfx(s.forces_.total(0)), gfy(s.forces_.total(1)),
        gfz(s.forces_.total(2)), gtx(s.forces_.total_torque(0)), gty(s.forces_.total_torque(1)),
        gtz(s.forces_.total_torque(2)), body(s.forces_.field()), inv_m(s.p_.inv_mass.data()),
        inv_i(s.p_.inv_inertia.data()), h(0.5 * s.dt_), gx(s.forces_.gravity()[0]),
        gy(s.forces_.gravity()[1]), gz(s.forces_.gravity()[2]) {}
  bool with_sources() const { return gfx != nullptr; }
  bool with_field() const { return body != nullptr; }
  /// dv and dw of particle i at position (x, y, z) (vx vy vz wx wy wz). Src: with the sources'
  /// forces; Field: a body force field may be there (tested per particle).
  template <bool Src, bool Field>
  [[gnu::always_inline]] std::array<double, 6> increment(std::size_t i, double x, double y,
                                                         double z) const {
    const double im = inv_m[i], ii = inv_i[i];
    const double* fc = contact + ContactScratch::kAcc * i; // force | torque | ...
    double fx = fc[0], fy = fc[1], fz = fc[2];
    if constexpr (Src) fx = fc[0] + gfx[i], fy = fc[1] + gfy[i], fz = fc[2] + gfz[i];
    std::array<double, 3> a{gx, gy, gz};
    if constexpr (Field) {
      if (body) {
        const auto b = body_acceleration(*body, x, y, z);
        a[0] += b[0], a[1] += b[1], a[2] += b[2];
      }
    }
    // A fixed particle (1/m = 0, 1/I = 0: infinite mass) gets no acceleration at all: its
    // forces and torques vanish with 1/m and 1/I, gravity and the body force here.
    if (im == 0.0) a = {0.0, 0.0, 0.0};
    double tx = fc[3], ty = fc[4], tz = fc[5];
    if constexpr (Src) {
      if (gtx != nullptr) tx = fc[3] + gtx[i], ty = fc[4] + gty[i], tz = fc[5] + gtz[i];
    }
    return {h * (fx * im + a[0]), h * (fy * im + a[1]), h * (fz * im + a[2]),
            h * tx * ii,          h * ty * ii,          h * tz * ii};
  }
  const double* contact;
  const double *gfx, *gfy, *gfz;
  const double *gtx, *gty, *gtz; ///< the sources' summed torques (nullptr: none)
  const BodyForceSpec* body;
  const double *inv_m, *inv_i;
  double h, gx, gy, gz;
};

void SoftSphereStepper::step(double time, const StepNeeds& needs_in) {
  StepNeeds needs = needs_in;
  // A dissipative source books its work after a finished second kick (finish_kick).
  if (forces_.books_work()) needs.defer_second_kick = false;
  const std::size_t n = p_.size();
  const auto& box = nl_->box();
  if (nc_.acc.size() != ContactScratch::kAcc * n)
    throw std::logic_error("SoftSphereStepper::step: the contact forces are not those of the "
                           "particles");
  const Kick kick(*this);
  // The arrays in locals (the stores below would otherwise make the compiler reload dt_ and
  // the array pointers for every particle).
  const double *const x = p_.x.data(), *const y = p_.y.data(), *const z = p_.z.data();
  const double *const vx = p_.vx.data(), *const vy = p_.vy.data(), *const vz = p_.vz.data();
  const double *const wx = p_.wx.data(), *const wy = p_.wy.data(), *const wz = p_.wz.data();
  const double *const inv_i = p_.inv_inertia.data(), *const inv_m = p_.inv_mass.data();
  const double* const radius = p_.radius.data();
  double* const view = nc_.view.data();
  const double dt = dt_;
  const bool any_periodic = box.periodic[0] || box.periodic[1] || box.periodic[2];
  // First half kick and drift; Wrap: periodic axes (centres kept inside [lo, hi)). In the same
  // pass, while the particle is in the cache: the contact loop's view of it is packed and its
  // sums zeroed (the kick has read the last forces), and its displacement since the last list
  // build tested (one parallel loop per step instead of three).
  // The pass writes the new positions and velocities to the view alone, which holds the state
  // from then on (p_'s arrays are brought up to date by sync_particles() when read). It reads
  // them from the view after a step that left its second kick pending (FromView: nothing has
  // read or changed p_ since, else the kick would have been finished), else from p_.
  const bool threaded = threaded_particles(n);
  const NeighbourList& list = *nl_;
  const bool tracked = list.built_for(n);
  // The state of particle i before the kicks: x y z | vx vy vz wx wy wz.
  const auto state = [&]<bool FromView>(std::size_t i) __attribute__((always_inline)) {
    if constexpr (FromView) {
      const double* vi = view + ContactScratch::kView * i;
      return std::array<double, 9>{vi[0], vi[1], vi[2], vi[4], vi[5], vi[6], vi[8], vi[9], vi[10]};
    } else {
      return std::array<double, 9>{x[i], y[i], z[i], vx[i], vy[i], vz[i], wx[i], wy[i], wz[i]};
    }
  };
  // Drift particle i from position q with its new velocities v and pack its view; returns
  // whether it moved more than skin/2 since the last list build (Check; else false).
  const auto drift = [&]<bool FromView, bool Wrap, bool Check = true>(
      std::size_t i, const std::array<double, 9>& q, const std::array<double, 6>& v)
      __attribute__((always_inline)) {
    double xi = q[0] + dt * v[0], yi = q[1] + dt * v[1], zi = q[2] + dt * v[2];
    if constexpr (Wrap) {
      if (box.periodic[0]) xi = wrapped(xi, box.lo[0], box.length(0));
      if (box.periodic[1]) yi = wrapped(yi, box.lo[1], box.length(1));
      if (box.periodic[2]) zi = wrapped(zi, box.lo[2], box.length(2));
    }
    if constexpr (FromView) // radius, mass and 1/I are in the view already
      nc_.pack_state(i, {xi, yi, zi, v[0], v[1], v[2], v[3], v[4], v[5]});
    else
      nc_.pack(i, {xi, yi, zi, radius[i], v[0], v[1], v[2], inv_m[i], v[3], v[4], v[5], inv_i[i]});
    if constexpr (Check)
      return tracked && list.moved_far(i, xi, yi, zi);
    else
      return false;
  };
  // A second half kick left pending by the last step (velocity Verlet: it and this step's
  // first kick both apply the last force evaluation, so they are the same increment) runs in
  // the same pass: v + dv, its dissipation term, + dv, drift; bitwise the operations of two
  // passes, one pass over the particles fewer.
  const bool fused = kick_pending_;
  kick_pending_ = false;
  // Particle i's pending second half kick, its dissipation terms, the first half kick and the
  // drift (with the rebuild test: Check), from and into the view; the separate pass and the
  // folded step's slab pass both run it, so that they stay bitwise the same.
  const auto kick_kick_drift = [&]<bool Src, bool Field, bool Wrap, bool Check>(std::size_t i)
      __attribute__((always_inline)) {
    const std::array<double, 9> q = state.template operator()<true>(i);
    const std::array<double, 6> dv = kick.increment<Src, Field>(i, q[0], q[1], q[2]);
    const std::array<double, 6> v{q[3] + dv[0], q[4] + dv[1], q[5] + dv[2],
                                  q[6] + dv[3], q[7] + dv[4], q[8] + dv[5]};
    const std::array<double, 2> t = nc_.dissipation_terms(i, v); // before the packing
    const bool far = drift.template operator()<true, Wrap, Check>(
        i, q, {v[0] + dv[0], v[1] + dv[1], v[2] + dv[2], v[3] + dv[3], v[4] + dv[4], v[5] + dv[5]});
    return ContactScratch::DissipationTerms{t[0], t[1], far};
  };
  const auto kick_drift = [&]<bool Src, bool Field, bool Wrap>() {
    if (!fused)
      return parallel_any(n, threaded, [&](std::size_t i) {
        const std::array<double, 9> q = state.template operator()<false>(i);
        const std::array<double, 6> dv = kick.increment<Src, Field>(i, q[0], q[1], q[2]);
        return drift.template operator()<false, Wrap>(
            i, q,
            {q[3] + dv[0], q[4] + dv[1], q[5] + dv[2], q[6] + dv[3], q[7] + dv[4], q[8] + dv[5]});
      });
    bool any = false;
    e_dsp_ += nc_.dissipation_sum(
        n, dt,
        [&](std::size_t i) __attribute__((always_inline)) {
          return kick_kick_drift.template operator()<Src, Field, Wrap, true>(i);
        },
        any);
    return any;
  };
  const bool plain = !kick.with_sources() && !kick.with_field();
  if (may_fold(fused, tracked, plain))
    folded_step(kick_kick_drift, any_periodic, needs);
  else
    separate_step(kick_drift, tracked, plain, needs);
  if (forces_.any_step_sources()) evaluate_step_sources(time + dt_);

  // The second half kick, after the forces: left for the next step when the caller asks (it
  // then reads no velocity before finish_kick()), else now. The continuum averages of this
  // step take the full-step velocities.
  kick_pending_ = true;
  if (!needs.defer_second_kick || needs.sample_continuum) finish_kick();
}

bool SoftSphereStepper::may_fold(bool fused, bool tracked, bool plain) const {
  // A folded step: when the second half kick is pending, the kick is plain (contact forces and
  // gravity: no sources, no body-force field) and the last step bounds this one's drift within
  // half the skin (DriftBound: no rebuild can be due after it), the step's pass runs inside the
  // contact loop, slab by slab, where the loop reads the particles anyway (one stream of the
  // particles through the cache per step instead of two; bench/RESULTS.md). Bitwise the same
  // particles as the separate pass (the same operations on each particle); the dissipation is
  // summed per slab (compute_forces_folded). Only in dense beds (fold_pairs_per_particle();
  // the same list as after the last step: a folded step does not build).
  const auto& g = forces_.gravity();
  return fold_enabled_ && plain && fused && tracked &&
         pairs_per_particle() >= fold_pairs_threshold &&
         drift_bound_.next_step_within(dt_, 0.5 * nl_->skin(), stats_.max_force2,
                                       nl_->max_entries_per_particle(), max_inv_mass_,
                                       std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]));
}

void SoftSphereStepper::folded_step(const auto& kick_kick_drift, bool any_periodic,
                                    const StepNeeds& needs) {
  // Slab sl's particles as in the separate pass, without its rebuild test; the slab's
  // dissipation sum and largest squared drift speed (read back from the view), for
  // compute_forces_folded. Wrap: periodic axes.
  const NeighbourList& list = *nl_;
  slab_sums_.resize(2 * static_cast<std::size_t>(list.slab_count())); // kept between steps
  double* const sums = slab_sums_.data();
  const std::uint32_t* const slab_start = list.slab_start.data();
  const std::uint32_t* const members = list.slab_particles.data();
  const double* const view = nc_.view.data();
  const auto slab_pass = [&, sums, slab_start, members, view]<bool Wrap>(int sl) {
    double w = 0.0, v2 = 0.0;
    for (std::uint32_t m = slab_start[sl]; m < slab_start[sl + 1]; ++m) {
      const std::size_t i = members[m];
      const ContactScratch::DissipationTerms t =
          kick_kick_drift.template operator()<false, false, Wrap, false>(i);
      w += t.force;
      w += t.torque;
      const double* vi = view + ContactScratch::kView * i;
      const double s2 = vi[4] * vi[4] + vi[5] * vi[5] + vi[6] * vi[6];
      v2 = s2 > v2 ? s2 : v2;
    }
    sums[2 * sl] = w, sums[2 * sl + 1] = v2;
  };
  particles_current_ = false;
  if (record_) record_->enabled = needs.record_contacts;
  compute_forces_folded(any_periodic
                            ? SlabHook([&](int sl) { slab_pass.template operator()<true>(sl); })
                            : SlabHook([&](int sl) { slab_pass.template operator()<false>(sl); }));
  ++folded_steps_;
}

void SoftSphereStepper::separate_step(const auto& kick_drift, bool tracked, bool plain,
                                      const StepNeeds& needs) {
  const std::size_t n = p_.size();
  const bool with_sources = forces_.total(0) != nullptr, with_field = forces_.field() != nullptr;
  const auto& box = nl_->box();
  const bool any_periodic = box.periodic[0] || box.periodic[1] || box.periodic[2];
  auto t0 = WallClock::now();
  bool moved_far;
  if (with_sources && !with_field && !any_periodic)
    moved_far = kick_drift.template operator()<true, false, false>();
  else if (!with_sources && !with_field && !any_periodic)
    moved_far = kick_drift.template operator()<false, false, false>();
  else if (with_sources)
    moved_far = kick_drift.template operator()<true, true, true>();
  else
    moved_far = kick_drift.template operator()<false, true, true>();
  particles_current_ = false;
  t_integration_ += seconds_since(t0);

  // The view stays packed unless the particles are reordered.
  ScratchState scratch = ScratchState::Packed;
  const bool rebuild = !tracked || moved_far;
  if (rebuild) sync_particles(); // the build reads the positions from p_
  t0 = WallClock::now();
  if (rebuild) {
    if (sort_interval_ > 0 && nl_->builds() % sort_interval_ == 0) {
      sort_and_rebuild();
      scratch = ScratchState::Stale;
    } else {
      nl_->build(p_);
    }
  }
  t_neighbour_ += seconds_since(t0);

  // The contacts are recorded on the steps whose contacts an analysis uses.
  if (record_) record_->enabled = needs.record_contacts;
  compute_forces(scratch);
  // What the next step's fold decision needs of this step (a folded step finds it in its own
  // pass; this is a pass of its own, on the steps that are not folded), when the next step may
  // fold: this step leaves its second kick pending.
  if (fold_enabled_ && plain && needs.defer_second_kick && !needs.sample_continuum) {
    if (pairs_per_particle() >= fold_pairs_threshold) {
      t0 = WallClock::now();
      drift_bound_.measure(nc_.view.data(), ContactScratch::kView, n, *nl_);
      t_integration_ += seconds_since(t0);
    } else {
      drift_bound_ = DriftBound{}; // unknown: a step after a build that makes it dense measures
    }
  }
}

void SoftSphereStepper::evaluate_step_sources(double t) {
  const auto t0 = WallClock::now();
  sync_particles(); // the sources read the store
  forces_.evaluate_step_sources(p_, t);
  t_sources_ += seconds_since(t0);
}

void SoftSphereStepper::compute_forces_folded(const SlabHook& slab_pass) {
  const auto t0 = WallClock::now();
  stats_ = compute_contact_forces(p_, *nl_, *table_, dt_, nc_, record_, ScratchState::Packed,
                                  &slab_pass);
  t_contacts_ += seconds_since(t0);
  // The slabs' sums in slab order (the same with any number of threads).
  double w = 0.0, v2 = 0.0;
  for (int sl = 0; sl < nl_->slab_count(); ++sl) {
    w += slab_sums_[2 * static_cast<std::size_t>(sl)];
    v2 = std::max(v2, slab_sums_[2 * static_cast<std::size_t>(sl) + 1]);
  }
  e_dsp_ += -w * dt_;
  e_dsp_ += stats_.spring_losses;
  drift_bound_.folded_step(dt_, v2);
}

void SoftSphereStepper::sync_particles() {
  if (particles_current_) return;
  const auto t0 = WallClock::now();
  const std::size_t n = p_.size();
  const double* view = nc_.view.data();
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    const double* vi = view + ContactScratch::kView * i;
    p_.x[i] = vi[0], p_.y[i] = vi[1], p_.z[i] = vi[2];
    p_.vx[i] = vi[4], p_.vy[i] = vi[5], p_.vz[i] = vi[6];
    p_.wx[i] = vi[8], p_.wy[i] = vi[9], p_.wz[i] = vi[10];
  });
  particles_current_ = true;
  t_integration_ += seconds_since(t0);
}

void SoftSphereStepper::finish_kick() {
  sync_particles(); // the callers read p_ (and the kick below works on it)
  if (!kick_pending_) return;
  kick_pending_ = false;
  const auto t0 = WallClock::now();
  // The second half kick, and in the same pass the work of the non-conservative contact forces
  // with the full-step velocities: with velocity Verlet the force computed at t+dt acts with
  // mean velocity v(t+dt) over [t+dt/2, t+3dt/2].
  const Kick kick(*this);
  double *const vx = p_.vx.data(), *const vy = p_.vy.data(), *const vz = p_.vz.data();
  double *const wx = p_.wx.data(), *const wy = p_.wy.data(), *const wz = p_.wz.data();
  const auto second_kick = [&]<bool Src, bool Field>() {
    return nc_.dissipated_after(
        p_, dt_, [&](std::size_t i) __attribute__((always_inline)) {
          const std::array<double, 6> dv = kick.increment<Src, Field>(i, p_.x[i], p_.y[i], p_.z[i]);
          const std::array<double, 6> v{vx[i] + dv[0], vy[i] + dv[1], vz[i] + dv[2],
                                        wx[i] + dv[3], wy[i] + dv[4], wz[i] + dv[5]};
          vx[i] = v[0], vy[i] = v[1], vz[i] = v[2];
          wx[i] = v[3], wy[i] = v[4], wz[i] = v[5];
          return v;
        });
  };
  const bool with_sources = kick.with_sources(), with_field = kick.with_field();
  if (with_sources && !with_field)
    e_dsp_ += second_kick.template operator()<true, false>();
  else if (!with_sources && !with_field)
    e_dsp_ += second_kick.template operator()<false, false>();
  else if (with_sources)
    e_dsp_ += second_kick.template operator()<true, true>();
  else
    e_dsp_ += second_kick.template operator()<false, true>();
  // The work of the dissipative sources with the same full-step velocities.
  if (forces_.books_work()) e_dsp_ += forces_.dissipated_work(p_, dt_);
  t_integration_ += seconds_since(t0);
}

void SoftSphereStepper::sort_and_rebuild() {
  // The list's own cells, so that the slabs of the sort are the list's.
  const std::vector<std::uint32_t> order = spatial_order(p_, nl_->box(), nl_->cell_size(p_));
  p_.permute(order); // (p_ is current: the callers synchronise it first)
  forces_.permute(order);
  nl_->build(p_, &order);
  ++sorts_;
}

} // namespace fluidem
