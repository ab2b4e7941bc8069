#include "integrate/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include <fmt/format.h>

#include "analysis/bed_height.hpp"
#include "core/nearest_integer.hpp"
#include "core/parallel.hpp"
#include "fluidem_version.hpp"
#include "integrate/contact_time_limit.hpp"
#include "integrate/memory_estimate.hpp"
#include "io/case_writer.hpp"
#include "neighbour/spatial_order.hpp"
#include "output/fields_writer.hpp"
#include "output/fields_xdmf.hpp"
#include "output/h5md_writer.hpp"
#include "output/series_writer.hpp"
#include "output/xdmf_writer.hpp"
#include "particles/insertion.hpp"

namespace fluidem {

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// At least this many particle steps per contact: below it the run is refused unless forced.
constexpr double kMinStepsPerContact = 10.0;
/// The automatic skin (neighbour.skin = "auto") lets a neighbour list last at least this many
/// steps at the largest particle speed of its build, within its bounds (NeighbourList::AutoSkin).
constexpr double kAutoSkinSteps = 10.0;
/// A run of more steps than this would not end in any useful time: refused.
constexpr double kMaxSteps = 1e12;
/// The integrator's pass folds into the contact loop (Simulation::step) only in beds with at
/// least this many neighbour-list pairs per particle (the default of
/// Simulation::fold_pairs_per_particle): there the contact loop streams every
/// particle through the cache anyway, and the fold saves the separate pass's stream (bed100k,
/// 5.0 pairs per particle: +6-7%; bed10k, 3.72: +1.5% on one thread, +4% on two). In sparser
/// beds the contact loop reads few particles, and the fold's pass, in slab order, ran slower
/// than the separate one in index order: 40 000 discs settled (2.79 pairs per particle) 1-2%
/// slower, falling (0.08) 3-5% (medians; up to 20% in single pairs), 40 000 falling spheres
/// (0.1) 4-5% (bench/RESULTS.md, 2026-12-04).
constexpr double kFoldPairsPerParticle = 3.0;
double fold_pairs_threshold = kFoldPairsPerParticle;

void check_step_count(const CaseSpec& spec, double dt) {
  const double steps = spec.simulation.end_time / dt;
  if (!(dt > 0.0) || !std::isfinite(steps) || steps > kMaxSteps)
    throw InputError(spec.where("simulation.time_step"), "simulation.time_step",
                     fmt::format("{:.4g} s gives {:.3g} steps to simulation.end_time = {:.4g} s "
                                 "(allowed: at most {:.0e} steps)",
                                 dt, steps, spec.simulation.end_time, kMaxSteps));
}

BoxGeometry box_from(const CaseSpec& spec) {
  BoxGeometry b;
  b.lo = spec.domain.lo;
  b.hi = spec.domain.hi;
  b.periodic = spec.domain.periodic;
  for (int f = 0; f < 6; ++f) {
    const int a = f / 2;
    b.wall[f] = !b.periodic[a] && !(spec.simulation.dimension == 2 && a == 1);
  }
  return b;
}

/// The shortest contact duration of the contacts that can happen, s. Fixed particles
/// (ParticleStore::fix) meet neither each other nor the walls, and a fixed partner has infinite
/// mass (m* = the moving particle's mass): the species pairs and walls that only fixed particles
/// could form do not limit the time step. Durations per species as ContactTable's; without
/// fixed particles its shortest. Infinity when no contact can happen (no particle moves).
double shortest_possible_contact(const CaseSpec& spec, const ParticleStore& p,
                                 const ContactTable& t) {
  const std::size_t ns = spec.species.size();
  std::vector<char> moving(ns, 0), fixed(ns, 0);
  for (std::size_t i = 0; i < p.size(); ++i)
    (p.fixed(i) ? fixed : moving)[static_cast<std::size_t>(p.species[i])] = 1;
  if (std::find(fixed.begin(), fixed.end(), 1) == fixed.end()) return t.shortest_contact_duration();
  double tc = std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < ns; ++a) {
    const double ra = 0.5 * spec.species[a].diameter;
    const double ma = sphere_mass(ra, spec.species[a].density);
    for (std::size_t b = 0; b < ns; ++b) {
      const double rb = 0.5 * spec.species[b].diameter;
      const double mb = sphere_mass(rb, spec.species[b].density);
      const PairParams& pp = t.pair(static_cast<int>(a), static_cast<int>(b));
      const double r_eff = ra * rb / (ra + rb);
      if (moving[a] && moving[b] && a <= b)
        tc = std::min(tc, t.contact_duration(ma * mb / (ma + mb), r_eff, pp, false));
      // (A fixed partner is met as a wall is: at one particle's speed.)
      if (moving[a] && fixed[b]) tc = std::min(tc, t.contact_duration(ma, r_eff, pp, true));
    }
    for (int f = 0; f < 6 && moving[a]; ++f) {
      if (spec.domain.periodic[f / 2] || (spec.simulation.dimension == 2 && f / 2 == 1)) continue;
      tc = std::min(tc, t.contact_duration(ma, ra, t.wall(static_cast<int>(a), f), true));
    }
  }
  return tc;
}

/// Overlap under the bed's own weight: a bottom particle carries the column above it,
/// F = m g h / d with h the height the particles fill at packing fraction 0.6 (3-D) or area
/// fraction 0.82 (2-D); delta = F/k_n (linear) or (F/K)^{2/3} (Hertz, against the floor).
double expected_overlap_ratio(const CaseSpec& spec, const ParticleStore& p, const ContactTable& t) {
  const auto& g = spec.simulation.gravity;
  const double gabs = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
  if (gabs == 0.0 || p.size() == 0 || spec.species.empty()) return 0.0;
  int down = 2; // the axis gravity points along
  for (int a = 0; a < 3; ++a)
    if (std::abs(g[a]) > std::abs(g[down])) down = a;
  double base = 1.0, solid = 0.0;
  const bool two_d = spec.simulation.dimension == 2;
  for (int a = 0; a < 3; ++a)
    if (a != down && !(two_d && a == 1)) base *= spec.domain.hi[a] - spec.domain.lo[a];
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double r = p.radius[i];
    solid += two_d ? std::numbers::pi * r * r : 4.0 / 3.0 * std::numbers::pi * r * r * r;
  }
  const double h = solid / ((two_d ? 0.82 : 0.6) * base);
  const auto& s = spec.species[0];
  const double r = 0.5 * s.diameter;
  const double f = sphere_mass(r, s.density) * gabs * h / s.diameter;
  const int face = 2 * down + (g[down] > 0 ? 1 : 0);
  const PairParams& pp = t.wall(0, face);
  return t.overlap_under(f, r, pp) / s.diameter;
}

/// OUT/collision_overlap.csv: the overlap-extent histogram of all pair collisions ended since
/// t = 0 (bins [bin_lo, bin_hi) of max overlap / smaller diameter; the last row, bin_hi = inf,
/// counts the extents above the range); fraction = count / all ended pair collisions.
void write_overlap_histogram(const std::string& path, const CollisionStatistics& c) {
  SeriesWriter w(path, {"bin_lo", "bin_hi", "count", "fraction"});
  const auto& h = c.histogram();
  const std::size_t nb = h.size() - 1;
  const double width = c.settings().histogram_max / static_cast<double>(nb);
  std::int64_t total = 0;
  for (const auto k : h) total += k;
  for (std::size_t k = 0; k <= nb; ++k) {
    const double lo = static_cast<double>(k) * width;
    const double hi =
        k < nb ? static_cast<double>(k + 1) * width : std::numeric_limits<double>::infinity();
    const auto count = static_cast<double>(h[k]);
    w.write_row({lo, hi, count, total > 0 ? count / static_cast<double>(total) : 0.0});
  }
  w.close();
}

} // namespace

Simulation::Simulation(CaseSpec spec) : Simulation(std::move(spec), nullptr) {}

Simulation::Simulation(CaseSpec spec, const ParticleStore* initial) : spec_(std::move(spec)) {
  const bool hard = spec_.simulation.engine == Engine::HardSphere;
  // Memory first: no table, particle or grid is allocated for a case that cannot fit.
  require_memory(spec_, case_memory_shares(spec_));
  if (!hard) {
    // The species with particles: those of the [[insert]] blocks (a restart's particles were
    // inserted by the same blocks).
    std::vector<bool> used(spec_.species.size(), false);
    for (const InsertSpec& ins : spec_.inserts)
      if (const int s = spec_.species_index(ins.species); s >= 0) used[s] = true;
    table_ = std::make_unique<ContactTable>(spec_, std::move(used));
    check_contact_durations(spec_, *table_, kMinStepsPerContact, kMaxSteps);
  }
  if (initial) {
    p_ = *initial;
  } else {
    insert_particles(spec_, p_);
    // Coloured layers [Hoomans96 Figs. 10, 12]: bands of the initial bed along gravity's axis.
    int up = 2;
    for (int a = 0; a < 3; ++a)
      if (std::abs(spec_.simulation.gravity[a]) > std::abs(spec_.simulation.gravity[up])) up = a;
    assign_layers(p_, up, spec_.output.layers);
  }
  p_.shrink_to_fit(); // insertion appended particle by particle
  if (!(spec_.output.checkpoint_interval > 0.0))
    spec_.output.checkpoint_interval = 10.0 * spec_.output.frame_interval;

  double dmax = 0.0, mass = 0.0;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    dmax = std::max(dmax, 2.0 * p_.radius[i]);
    mass += p_.mass[i];
  }
  for (const auto& s : spec_.species) dmax = std::max(dmax, s.diameter);
  for (const double im : p_.inv_mass) max_inv_mass_ = std::max(max_inv_mass_, im);
  const double skin = spec_.neighbour.skin ? *spec_.neighbour.skin : 0.2 * dmax;
  if (table_)
    for (const int s : p_.species) // (every particle's species has its contact coefficients)
      if (!table_->has_particles(s))
        throw std::logic_error("a particle of species " + spec_.species[s].name +
                               ", which no [[insert]] names");
  // With the particles known (the neighbour lists' cell grids are bounded by the particle count,
  // neighbour/cell_grid.hpp, and counted in their bytes per particle).
  require_memory(spec_, case_memory_shares(spec_, static_cast<double>(p_.size())));

  if (spec_.output.collisions) {
    CollisionStatistics::Settings cs;
    for (const CollisionRegionSpec& r : spec_.output.collision_regions)
      cs.regions.push_back({r.name, Vec3{r.centre[0], r.centre[1], r.centre[2]}, r.radius});
    cs.dimension = spec_.simulation.dimension;
    for (std::size_t a = 0; a < 3; ++a) {
      cs.box_length[a] = spec_.domain.hi[a] - spec_.domain.lo[a];
      cs.periodic[a] = spec_.domain.periodic[a];
    }
    collisions_ = std::make_unique<CollisionStatistics>(std::move(cs), 0.0);
    record_.enabled = true;
  }

  report_.particle_count = p_.size();
  report_.total_mass = mass;
  report_.skin = skin;
  if (hard) {
    // The flow time step DT of the collision sequence [Hoomans96 Fig. 3]; "auto" = 1e-4 s
    // [Hoomans96 Table 2]. Collisions are events, so there is no contact-time limit.
    const auto& sim = spec_.simulation;
    dt_ = sim.time_step ? *sim.time_step : 1.0e-4;
    if (!sim.time_step && sim.end_time > 0.0) dt_ = sim.end_time / std::ceil(sim.end_time / dt_);
    spec_.simulation.time_step = dt_;
    report_.chosen_time_step = dt_;
    check_step_count(spec_, dt_);
    nl_ = std::make_unique<NeighbourList>(box_from(spec_), skin, 0);
    hard_ = std::make_unique<HardSphereEngine>(spec_, box_from(spec_));
    hard_->set_record_collisions(collisions_ != nullptr);
    if (spec_.gas) {
      if (spec_.gas->time_step != 0.0)
        throw InputError(spec_.where("gas.time_step"), "gas.time_step",
                         "hard-sphere runs take the flow step DT from simulation.time_step; "
                         "remove gas.time_step");
      report_.flow_time_step = dt_;
      gas_ = std::make_unique<GasCoupling>(spec_, p_);
    }
    return;
  }

  // Time step from the contact duration [Deen07 eq. 41-42] of the contacts that can happen.
  // None (every particle fixed): 1e-4 s, the flow step's default, unless given.
  const double tc = shortest_possible_contact(spec_, p_, *table_);
  const double dt_limit = tc / kMinStepsPerContact;
  const auto& sim = spec_.simulation;
  dt_ = sim.time_step ? *sim.time_step : std::isfinite(tc) ? sim.time_step_fraction * tc : 1.0e-4;
  // An automatic step is shortened so that a whole number of steps ends exactly at end_time.
  if (!sim.time_step && sim.end_time > 0.0) dt_ = sim.end_time / std::ceil(sim.end_time / dt_);
  if (dt_ > dt_limit && !sim.force_time_step) {
    throw InputError(spec_.where("simulation.time_step"), "simulation.time_step",
                     fmt::format("{:.4g} s is above the stability limit {:.4g} s (the shortest "
                                 "contact lasts {:.4g} s and needs at least {} steps); choose a "
                                 "smaller step, \"auto\", or set simulation.force_time_step = "
                                 "true",
                                 dt_, dt_limit, tc, kMinStepsPerContact));
  }
  if (spec_.gas) {
    // Flow step DT ("auto" = 1e-4 s [Hoomans96 §5.3], shortened to end exactly at end_time);
    // the DEM step is shortened so that a whole number of DEM steps fills DT.
    double flow_dt = spec_.gas->time_step > 0.0 ? spec_.gas->time_step : 1.0e-4;
    if (spec_.gas->time_step == 0.0 && sim.end_time > 0.0)
      flow_dt = sim.end_time / std::ceil(sim.end_time / flow_dt);
    steps_per_flow_ = std::max(1L, static_cast<long>(std::ceil(flow_dt / dt_ - 1e-9)));
    dt_ = flow_dt / static_cast<double>(steps_per_flow_);
    spec_.gas->time_step = flow_dt;
    report_.flow_time_step = flow_dt;
    report_.steps_per_flow_step = steps_per_flow_;
  }
  spec_.simulation.time_step = dt_; // the resolved case reproduces this run
  check_step_count(spec_, dt_);

  report_.durations = table_->durations();
  report_.characteristic_velocity = table_->characteristic_velocity();
  report_.stable_time_step = dt_limit;
  report_.chosen_time_step = dt_;
  report_.time_step_forced = dt_ > dt_limit;
  report_.expected_overlap_ratio = expected_overlap_ratio(spec_, p_, *table_);

  if (const auto& c = spec_.output.continuum) {
    // Discrete-to-continuum averages [Zhu07 Tables 5-6] on cells over the whole domain.
    ContinuumGrid grid;
    grid.cells = c->cells;
    grid.lo = spec_.domain.lo;
    grid.periodic = spec_.domain.periodic;
    grid.dimension = spec_.simulation.dimension;
    for (int a = 0; a < 3; ++a)
      grid.spacing[a] = (spec_.domain.hi[a] - spec_.domain.lo[a]) / c->cells[a];
    ContinuumSettings settings;
    settings.method = c->method == ContinuumMethod::Weighted ? AveragingMethod::Weighted
                                                             : AveragingMethod::Volume;
    settings.width = c->width;
    settings.cutoff = c->cutoff;
    try {
      continuum_ = std::make_unique<ContinuumAverager>(grid, settings);
    } catch (const std::invalid_argument& e) {
      throw InputError(spec_.where("output.continuum"), "output.continuum", e.what());
    }
    continuum_interval_ = c->interval > 0.0 ? c->interval : spec_.output.frame_interval;
  }

  nl_ = std::make_unique<NeighbourList>(box_from(spec_), skin, contact_history_width(*table_));
  // neighbour.skin = "auto": each build chooses its skin from the particles' speeds, for lists
  // that last kAutoSkinSteps steps, between 0.2 and 1 largest diameter (NeighbourList::AutoSkin).
  if (!spec_.neighbour.skin) nl_->set_auto_skin({dt_, kAutoSkinSteps, skin, dmax});
  // A new run starts sorted in space (inserted at random or read from a file in any order); a
  // restarted one continues in the order of its checkpoint.
  if (!initial && spec_.neighbour.sort_interval > 0)
    sort_and_rebuild(); // the first build, so no history to carry over
  else
    nl_->build(p_);
  report_.skin = nl_->skin(); // the first build's
  compute_forces();
  if (spec_.gas) gas_ = std::make_unique<GasCoupling>(spec_, p_);
}

Simulation::~Simulation() = default;

void Simulation::compute_forces(ScratchState scratch) {
  const auto t0 = Clock::now();
  // The contacts are recorded when an analysis uses them: the collision statistics every step,
  // the continuum averages on their sampled steps (Simulation::step sets record_.enabled).
  stats_ = compute_contact_forces(p_, *nl_, *table_, dt_, nc_,
                                  collisions_ || continuum_ ? &record_ : nullptr, scratch);
  t_contacts_ += seconds_since(t0);
  e_dsp_ += stats_.spring_losses;
}

/// The half kick of a particle with the last force evaluation, dv = ((F + F_gas)/m + g + a(x))
/// dt/2, dw = T/I dt/2; a(x) is the body force field at the particle's current position
/// (velocity Verlet with a position-dependent force: x^n in the first half kick, x^{n+1} in the
/// second). The contact forces and torques are in nc_ (ContactScratch): a step's first kick
/// reads the previous step's, the second this step's.
struct Simulation::Kick {
  explicit Kick(const Simulation& s)
      : contact(s.nc_.acc.data()), gfx(s.gas_ ? s.gas_->force(0).data() : nullptr),
        gfy(s.gas_ ? s.gas_->force(1).data() : nullptr),
        gfz(s.gas_ ? s.gas_->force(2).data() : nullptr),
        body(s.spec_.body_force ? &*s.spec_.body_force : nullptr), inv_m(s.p_.inv_mass.data()),
        inv_i(s.p_.inv_inertia.data()), h(0.5 * s.dt_), gx(s.spec_.simulation.gravity[0]),
        gy(s.spec_.simulation.gravity[1]), gz(s.spec_.simulation.gravity[2]) {}
  bool with_gas() const { return gfx != nullptr; }
  bool with_field() const { return body != nullptr; }
  /// dv and dw of particle i at position (x, y, z) (vx vy vz wx wy wz). Gas: with gas forces;
  /// Field: a body force field may be there (tested per particle).
  template <bool Gas, bool Field>
  [[gnu::always_inline]] std::array<double, 6> increment(std::size_t i, double x, double y,
                                                         double z) const {
    const double im = inv_m[i], ii = inv_i[i];
    const double* fc = contact + ContactScratch::kAcc * i; // force | torque | ...
    double fx = fc[0], fy = fc[1], fz = fc[2];
    if constexpr (Gas) fx = fc[0] + gfx[i], fy = fc[1] + gfy[i], fz = fc[2] + gfz[i];
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
    return {h * (fx * im + a[0]), h * (fy * im + a[1]), h * (fz * im + a[2]),
            h * fc[3] * ii,       h * fc[4] * ii,       h * fc[5] * ii};
  }
  const double* contact;
  const double *gfx, *gfy, *gfz;
  const BodyForceSpec* body;
  const double *inv_m, *inv_i;
  double h, gx, gy, gz;
};

void Simulation::step(bool defer_second_kick) {
  if (hard_) {
    if (gas_) { // [Hoomans96 Fig. 7]: flow step, then drag kick, then the collision sequence
      const auto tg = Clock::now();
      gas_->step(p_, time_, dt_);
      gas_->kick(p_, dt_);
      t_gas_ += seconds_since(tg);
    }
    // A space-varying body force (`[body_force]`) cannot be flown on exact parabolas: it acts
    // as two half kicks around the collision sequence (kick-drift-kick, second order in DT),
    // each with the acceleration at the particle's position at the time, like the gas forces
    // [Hoomans96 Fig. 7] which act as one kick per DT.
    body_force_kick(0.5 * dt_);
    const auto t0 = Clock::now();
    hard_->advance(p_, time_, dt_, spec_.simulation.gravity);
    body_force_kick(0.5 * dt_);
    e_dsp_ = hard_->stats().dissipated;
    t_contacts_ += seconds_since(t0);
    ++step_;
    time_ = static_cast<double>(step_) * dt_;
    record_collisions();
    return;
  }
  if (gas_ && step_ % steps_per_flow_ == 0) { // a flow step; its forces act over the next DT
    finish_kick(); // the gas step reads the particles' full-step velocities
    const auto tg = Clock::now();
    gas_->step(p_, time_, dt_ * static_cast<double>(steps_per_flow_));
    t_gas_ += seconds_since(tg);
  }
  const std::size_t n = p_.size();
  const auto& box = nl_->box();
  if (nc_.acc.size() != ContactScratch::kAcc * n)
    throw std::logic_error("Simulation::step: the contact forces are not those of the particles");
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
  // drift (with the rebuild test: Check), from and into the view; the pass below and the folded
  // step's slab pass (compute_forces_folded) both run it, so that they stay bitwise the same.
  const auto kick_kick_drift = [&]<bool Gas, bool Field, bool Wrap, bool Check>(std::size_t i)
      __attribute__((always_inline)) {
    const std::array<double, 9> q = state.template operator()<true>(i);
    const std::array<double, 6> dv = kick.increment<Gas, Field>(i, q[0], q[1], q[2]);
    const std::array<double, 6> v{q[3] + dv[0], q[4] + dv[1], q[5] + dv[2],
                                  q[6] + dv[3], q[7] + dv[4], q[8] + dv[5]};
    const std::array<double, 2> t = nc_.dissipation_terms(i, v); // before the packing
    const bool far = drift.template operator()<true, Wrap, Check>(
        i, q, {v[0] + dv[0], v[1] + dv[1], v[2] + dv[2], v[3] + dv[3], v[4] + dv[4], v[5] + dv[5]});
    return ContactScratch::DissipationTerms{t[0], t[1], far};
  };
  const auto kick_drift = [&]<bool Gas, bool Field, bool Wrap>() {
    if (!fused)
      return parallel_any(n, threaded, [&](std::size_t i) {
        const std::array<double, 9> q = state.template operator()<false>(i);
        const std::array<double, 6> dv = kick.increment<Gas, Field>(i, q[0], q[1], q[2]);
        return drift.template operator()<false, Wrap>(
            i, q,
            {q[3] + dv[0], q[4] + dv[1], q[5] + dv[2], q[6] + dv[3], q[7] + dv[4], q[8] + dv[5]});
      });
    bool any = false;
    e_dsp_ += nc_.dissipation_sum(
        n, dt,
        [&](std::size_t i) __attribute__((always_inline)) {
          return kick_kick_drift.template operator()<Gas, Field, Wrap, true>(i);
        },
        any);
    return any;
  };
  const bool with_gas = kick.with_gas(), with_field = kick.with_field();
  const bool sample_continuum = continuum_ && continuum_samples_next_step();
  // A folded step: when the second half kick is pending, the kick is plain (contact forces and
  // gravity: no gas forces, no body-force field) and the last step bounds this one's drift within
  // half the skin (DriftBound: no rebuild can be due after it), kick_drift's pass runs inside the
  // contact loop, slab by slab, where the loop reads the particles anyway (one stream of the
  // particles through the cache per step instead of two: +6-7% at 10^5 particles on one and two
  // threads, none at 10^4, which fits in the cache; bench/RESULTS.md). Bitwise the same
  // particles as kick_drift's pass (the same operations on each particle); the dissipation is
  // summed per slab (compute_forces_folded).
  const bool plain = !with_gas && !with_field;
  const auto& g = spec_.simulation.gravity;
  // fold_pairs_per_particle(); the same list as after the last step (a folded step does not
  // build).
  const auto dense = [this] { return neighbour_pairs_per_particle() >= fold_pairs_threshold; };
  if (fold_enabled_ && plain && fused && tracked && dense() &&
      drift_bound_.next_step_within(dt, 0.5 * list.skin(), stats_.max_force2,
                                    list.max_entries_per_particle(), max_inv_mass_,
                                    std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]))) {
    // Slab sl's particles as in kick_drift's pass, without its rebuild test; the slab's
    // dissipation sum and largest squared drift speed (read back from the view), for
    // compute_forces_folded. Wrap: periodic axes.
    slab_sums_.resize(2 * static_cast<std::size_t>(list.slab_count())); // kept between steps
    double* const sums = slab_sums_.data();
    const std::uint32_t* const slab_start = list.slab_start.data();
    const std::uint32_t* const members = list.slab_particles.data();
    const auto slab_pass = [&, sums, slab_start, members]<bool Wrap>(int sl) {
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
    record_.enabled = collisions_ != nullptr || sample_continuum;
    compute_forces_folded(any_periodic
                              ? SlabHook([&](int sl) { slab_pass.operator()<true>(sl); })
                              : SlabHook([&](int sl) { slab_pass.operator()<false>(sl); }));
    ++folded_steps_;
  } else {
    auto t0 = Clock::now();
    bool moved_far;
    if (with_gas && !with_field && !any_periodic)
      moved_far = kick_drift.template operator()<true, false, false>();
    else if (!with_gas && !with_field && !any_periodic)
      moved_far = kick_drift.template operator()<false, false, false>();
    else if (with_gas)
      moved_far = kick_drift.template operator()<true, true, true>();
    else
      moved_far = kick_drift.template operator()<false, true, true>();
    particles_current_ = false;
    t_integration_ += seconds_since(t0);

    // The view stays packed unless the particles are reordered.
    ScratchState scratch = ScratchState::Packed;
    const bool rebuild = !tracked || moved_far;
    if (rebuild) sync_particles(); // the build reads the positions from p_
    t0 = Clock::now();
    if (rebuild) {
      const int every = spec_.neighbour.sort_interval;
      if (every > 0 && nl_->builds() % every == 0) {
        sort_and_rebuild();
        scratch = ScratchState::Stale;
      } else {
        nl_->build(p_);
      }
    }
    t_neighbour_ += seconds_since(t0);

    // The contacts are recorded on the steps whose contacts an analysis uses.
    record_.enabled = collisions_ != nullptr || sample_continuum;
    compute_forces(scratch);
    // What the next step's fold decision needs of this step (a folded step finds it in its
    // own pass; this is a pass of its own, on the steps that are not folded), when the next
    // step may fold: this step leaves its second kick pending.
    if (fold_enabled_ && plain && defer_second_kick && !sample_continuum) {
      if (dense()) {
        t0 = Clock::now();
        drift_bound_.measure(nc_.view.data(), ContactScratch::kView, n, list);
        t_integration_ += seconds_since(t0);
      } else {
        drift_bound_ = DriftBound{}; // unknown: a step after a build that makes it dense measures
      }
    }
  }

  // The second half kick, after the forces: left for the next step when the caller asks (it
  // then reads no velocity before finish_kick()), else now. The continuum averages of this
  // step take the full-step velocities.
  kick_pending_ = true;
  if (!defer_second_kick || sample_continuum) finish_kick();
  if (sample_continuum) // positions and contacts of this step, full-step velocities
    continuum_->accumulate(p_, record_.samples);
  ++step_;
  time_ = static_cast<double>(step_) * dt_;
  record_collisions();
}

double Simulation::fold_pairs_per_particle() {
  return fold_pairs_threshold;
}

void Simulation::set_fold_pairs_per_particle(double pairs) {
  fold_pairs_threshold = pairs;
}

void Simulation::compute_forces_folded(const SlabHook& slab_pass) {
  const auto t0 = Clock::now();
  stats_ = compute_contact_forces(p_, *nl_, *table_, dt_, nc_,
                                  collisions_ || continuum_ ? &record_ : nullptr,
                                  ScratchState::Packed, &slab_pass);
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

void Simulation::sync_particles() {
  if (particles_current_) return;
  const auto t0 = Clock::now();
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

void Simulation::finish_kick() {
  sync_particles(); // the callers read p_ (and the kick below works on it)
  if (!kick_pending_) return;
  kick_pending_ = false;
  const auto t0 = Clock::now();
  // The second half kick, and in the same pass the work of the non-conservative contact forces
  // with the full-step velocities: with velocity Verlet the force computed at t+dt acts with
  // mean velocity v(t+dt) over [t+dt/2, t+3dt/2].
  const Kick kick(*this);
  double *const vx = p_.vx.data(), *const vy = p_.vy.data(), *const vz = p_.vz.data();
  double *const wx = p_.wx.data(), *const wy = p_.wy.data(), *const wz = p_.wz.data();
  const auto second_kick = [&]<bool Gas, bool Field>() {
    return nc_.dissipated_after(
        p_, dt_, [&](std::size_t i) __attribute__((always_inline)) {
          const std::array<double, 6> dv = kick.increment<Gas, Field>(i, p_.x[i], p_.y[i], p_.z[i]);
          const std::array<double, 6> v{vx[i] + dv[0], vy[i] + dv[1], vz[i] + dv[2],
                                        wx[i] + dv[3], wy[i] + dv[4], wz[i] + dv[5]};
          vx[i] = v[0], vy[i] = v[1], vz[i] = v[2];
          wx[i] = v[3], wy[i] = v[4], wz[i] = v[5];
          return v;
        });
  };
  const bool with_gas = kick.with_gas(), with_field = kick.with_field();
  if (with_gas && !with_field)
    e_dsp_ += second_kick.template operator()<true, false>();
  else if (!with_gas && !with_field)
    e_dsp_ += second_kick.template operator()<false, false>();
  else if (with_gas)
    e_dsp_ += second_kick.template operator()<true, true>();
  else
    e_dsp_ += second_kick.template operator()<false, true>();
  t_integration_ += seconds_since(t0);
}

void Simulation::sort_and_rebuild() {
  // The list's own cells, so that the slabs of the sort are the list's.
  const std::vector<std::uint32_t> order = spatial_order(p_, nl_->box(), nl_->cell_size(p_));
  p_.permute(order); // (p_ is current: the callers synchronise it first)
  if (gas_) gas_->permute(order);
  nl_->build(p_, &order);
  output_order_valid_ = false;
  ++sorts_;
}

void Simulation::record_collisions() {
  if (!collisions_) return;
  if (hard_) {
    instant_.clear();
    for (const HardSphereCollision& c : hard_->last_step_collisions())
      instant_.push_back({c.id_a, c.id_b, c.point});
    collisions_->add_instant_step(instant_, p_, time_);
  } else {
    collisions_->add_step(record_, p_, time_);
  }
}

bool Simulation::continuum_samples_next_step() const {
  return continuum_ && (step_ + 1) % spec_.output.continuum->stride == 0;
}

void Simulation::body_force_kick(double h) {
  if (!spec_.body_force) return;
  const BodyForceSpec& b = *spec_.body_force;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (p_.fixed(i)) continue;
    const auto a = body_acceleration(b, p_.x[i], p_.y[i], p_.z[i]);
    p_.vx[i] += h * a[0];
    p_.vy[i] += h * a[1];
    p_.vz[i] += h * a[2];
  }
}

double Simulation::bed_height() const {
  const auto& g = spec_.simulation.gravity;
  int axis = 2;
  for (int d = 0; d < 3; ++d)
    if (std::abs(g[static_cast<std::size_t>(d)]) > std::abs(g[static_cast<std::size_t>(axis)]))
      axis = d;
  const bool upward = g[static_cast<std::size_t>(axis)] <= 0.0;
  const double floor = upward ? spec_.domain.lo[static_cast<std::size_t>(axis)]
                              : spec_.domain.hi[static_cast<std::size_t>(axis)];
  return fluidem::bed_height(p_, axis, floor, upward, spec_.simulation.dimension == 2);
}

void Simulation::check_stability() {
  finish_kick();
  const auto where = fmt::format("at t = {:.6g} s (step {})", time_, step_);
  const auto& box = nl_->box();
  for (std::size_t i = 0; i < p_.size(); ++i) {
    const double q[9] = {p_.x[i],  p_.y[i],  p_.z[i],  p_.vx[i], p_.vy[i],
                         p_.vz[i], p_.wx[i], p_.wy[i], p_.wz[i]};
    for (double v : q) {
      if (!std::isfinite(v)) {
        throw InstabilityError(fmt::format("run unstable {}: particle {} has a non-finite "
                                           "position or velocity",
                                           where, p_.id[i]));
      }
    }
    for (int a = 0; a < 3; ++a) {
      if (box.periodic[a] || (spec_.simulation.dimension == 2 && a == 1)) continue;
      if (q[a] < box.lo[a] - p_.radius[i] || q[a] > box.hi[a] + p_.radius[i]) {
        throw InstabilityError(fmt::format("run unstable {}: particle {} left the closed domain "
                                           "along {} ({} = {:.6g} m, domain [{}, {}])",
                                           where, p_.id[i], "xyz"[a], "xyz"[a], q[a], box.lo[a],
                                           box.hi[a]));
      }
    }
  }
  // After the per-particle checks: a particle that went through a wall is reported as having
  // left the domain rather than as overlapping the wall.
  if (stats_.max_overlap_ratio > spec_.contact.max_overlap) {
    throw InstabilityError(fmt::format(
        "run unstable {}: particle {} overlaps a neighbour or wall by {:.3g} of its diameter "
        "(limit contact.max_overlap = {}); reduce simulation.time_step",
        where, stats_.max_overlap_particle, stats_.max_overlap_ratio, spec_.contact.max_overlap));
  }
}

void Simulation::advance(long n) {
  for (long k = 0; k < n; ++k) {
    step(k + 1 < n); // the last step's second kick not deferred
    if (stats_.max_overlap_ratio > spec_.contact.max_overlap) check_stability();
  }
}

long Simulation::total_steps() const {
  return static_cast<long>(std::ceil(spec_.simulation.end_time / dt_ - 1e-9));
}

OutputLayout Simulation::output_layout() const {
  OutputLayout l;
  l.particles = p_.size();
  l.dimension = spec_.simulation.dimension;
  l.box = H5mdBox{spec_.domain.lo, spec_.domain.hi, spec_.domain.periodic};
  l.layers = spec_.output.layers > 0;
  std::vector<std::string> columns{"time",
                                   "e_kin",
                                   "e_rot",
                                   "e_pot",
                                   "e_el",
                                   "e_dsp",
                                   "e_total",
                                   "n_contacts",
                                   "max_overlap_ratio",
                                   "neighbour_builds"};
  if (hard_) {
    // n_contacts is then the number of collisions in the last flow step; n_collisions is
    // cumulative; n_tc_elastic and n_slow_elastic count collisions the TC model and the
    // low-speed rule made elastic (cumulative), e_tc_kept the energy they would have
    // dissipated; neighbour_builds counts the hard-sphere engine's list builds.
    columns.insert(columns.end(), {"n_collisions", "n_tc_elastic", "n_slow_elastic", "e_tc_kept"});
  }
  if (gas_) {
    // Coupled runs: e_total then leaves out the work of the gas on the particles.
    columns.insert(columns.end(),
                   {"pressure_drop", "bed_height", "gas_iterations", "superficial_velocity"});
  }
  l.csv["series.csv"] = columns;
  if (gas_ && !spec_.output.probes.empty()) {
    std::vector<std::string> pc{"time"};
    for (const ProbeSpec& pr : spec_.output.probes) pc.push_back(pr.name);
    l.csv["probes.csv"] = pc;
  }
  if (collisions_) { // analysis/collision_statistics.hpp; one row per series interval
    std::vector<std::string> cc{
        "time",           "pair_collisions",     "wall_collisions",    "collision_frequency",
        "mean_free_time", "mean_overlap_extent", "max_overlap_extent", "mean_contact_duration"};
    for (const CollisionRegionSpec& r : spec_.output.collision_regions)
      cc.insert(cc.end(), {r.name + "_collision_frequency", r.name + "_void_fraction",
                           r.name + "_particles"});
    l.csv["collisions.csv"] = cc;
  }
  if (gas_) { // gas fields per particle frame
    const auto& g = gas_->solver().grid();
    l.fields = OutputLayout::Grid{
        FieldGrid{g.n, g.lo, g.h}, {"porosity", "pressure"}, {"gas_velocity", "solids_velocity"}};
  }
  if (continuum_) {
    // Continuum averages [Zhu07 Tables 5-6]: one frame at the end of every averaging interval,
    // the cells as ParaView cell data. Tensor T_ab as the scalar <name>_<a><b>.
    OutputLayout::Grid c;
    c.grid = FieldGrid{continuum_->grid().cells, continuum_->grid().lo, continuum_->grid().spacing};
    c.scalars = {"solid_fraction", "granular_temperature"};
    for (const char* tensor : {"kinetic_stress", "contact_stress", "couple_stress"})
      for (const char* ab : {"xx", "xy", "xz", "yx", "yy", "yz", "zx", "zy", "zz"})
        c.scalars.push_back(std::string(tensor) + "_" + ab);
    c.vectors = {"velocity", "angular_velocity"};
    l.continuum = c;
  }
  return l;
}

double Simulation::output_bytes_needed() const {
  // What the rest of the run writes: particle frames (about 14 values of 8 bytes per particle),
  // gas field frames (8 values per cell), continuum frames (33 values per cell), CSV rows (up to
  // 18 characters a value), and the checkpoint twice (current and previous, about 26 values per
  // particle and 10 per cell); with a margin of 2. Outputs come at most once a step.
  const double remaining = std::max(0.0, spec_.simulation.end_time - time_);
  const double steps = std::ceil(remaining / dt_) + 1.0;
  const auto count = [&](double interval) {
    return std::min(std::floor(remaining / interval) + 2.0, steps + 1.0);
  };
  const double n = static_cast<double>(p_.size());
  const OutputLayout l = output_layout();
  const double cells = l.fields ? static_cast<double>(l.fields->grid.size()) : 0.0;
  double need = count(spec_.output.frame_interval) * (14.0 * 8.0 * n + 8.0 * 8.0 * cells);
  if (l.continuum)
    need += count(continuum_interval_) * 33.0 * 8.0 * static_cast<double>(l.continuum->grid.size());
  for (const auto& [name, columns] : l.csv)
    need += count(spec_.output.series_interval) * 18.0 * static_cast<double>(columns.size());
  need += 2.0 * (26.0 * 8.0 * n + 10.0 * 8.0 * cells);
  return 2.0 * need;
}

RunSummary Simulation::run(const std::string& out_dir,
                           const std::function<void(const RunStatus&)>& progress,
                           const RunOptions& options) {
  namespace fs = std::filesystem;
  // The directory, locked for the run: the caller's (which checked it), or taken here (a new
  // run then replaces whatever results were there).
  std::optional<OutputDirectory> own_dir;
  if (options.directory == nullptr) {
    own_dir.emplace(out_dir, "this run");
    own_dir->refuse_links();
    if (!options.resume) own_dir->remove_results();
  }
  const OutputDirectory& dir = options.directory ? *options.directory : *own_dir;
  const std::string resolved = write_case_toml(spec_);
  RunOutputs outputs = options.resume
                           ? RunOutputs::resume(dir, output_layout(), marks_, resolved, kVersion)
                           : RunOutputs::start(dir, output_layout(), resolved, kVersion);
  outputs_ = &outputs;
  struct Detach { // the outputs live in this call only
    const RunOutputs*& p;
    ~Detach() { p = nullptr; }
  } detach{outputs_};
  const std::string checkpoint_path = dir.file("checkpoint.h5");
  if (continuum_ && !clock_.started) clock_.next_continuum = time_ + continuum_interval_;
  SeriesWriter& series = outputs.csv("series.csv");
  SeriesWriter* probes = outputs.has_csv("probes.csv") ? &outputs.csv("probes.csv") : nullptr;
  SeriesWriter* coll = outputs.has_csv("collisions.csv") ? &outputs.csv("collisions.csv") : nullptr;
  H5mdWriter& h5 = outputs.particles();
  FieldsWriter* fields = outputs.fields();
  FieldsWriter* cont = outputs.continuum();
  CellFields cells;

  // The run ends at the first step at or after end_time; outputs are written at the first step
  // at or after each multiple of their interval (no drift from rounding intervals to steps).
  const double eps = 1e-9 * dt_;
  const long total = total_steps();
  const double frame_dt = spec_.output.frame_interval, series_dt = spec_.output.series_interval,
               checkpoint_dt = spec_.output.checkpoint_interval;
  if (!clock_.started) {
    clock_.next_frame = clock_.next_series = time_;
    clock_.next_checkpoint = time_ + checkpoint_dt;
  }
  const long check_every = 100;
  const long progress_every = std::max(1L, std::min(200L, 2000000L / std::max<long>(1, p_.size())));
  double seconds_output = 0.0;

  auto write_outputs = [&]() {
    // Nothing unstable reaches the files: check before any row or frame is written (which also
    // finishes a pending half kick: its time counted as integration, not output).
    const bool continuum_due = cont && time_ >= clock_.next_continuum - eps;
    const bool due = time_ >= clock_.next_series - eps || time_ >= clock_.next_frame - eps ||
                     step_ == total || continuum_due;
    if (due) finish_kick();
    const auto t0 = Clock::now();
    if (due) check_stability();
    if (time_ >= clock_.next_series - eps || step_ == total) {
      while (clock_.next_series <= time_ + eps) clock_.next_series += series_dt;
      const Energies e = energies();
      const double tot = e.kinetic + e.rotational + e.potential + stats_.elastic_energy + e_dsp_;
      if (!clock_.started) {
        clock_.e0 = tot;
        clock_.escale = std::max(std::abs(tot), 1e-300);
      }
      std::vector<double> row{time_,
                              e.kinetic,
                              e.rotational,
                              e.potential,
                              stats_.elastic_energy,
                              e_dsp_,
                              tot,
                              static_cast<double>(stats_.n_contacts),
                              stats_.max_overlap_ratio,
                              static_cast<double>(nl_->builds())};
      if (hard_) {
        const auto& h = hard_->stats();
        row[7] = static_cast<double>(h.events_last_step);
        row[9] = static_cast<double>(hard_->list_builds());
        row.insert(row.end(), {static_cast<double>(h.collisions), static_cast<double>(h.tc_elastic),
                               static_cast<double>(h.slow_elastic), h.tc_energy_kept});
      }
      if (gas_) {
        row.insert(row.end(), {gas_->pressure_drop(), bed_height(),
                               static_cast<double>(gas_->solver().last_iterations()),
                               gas_->superficial_velocity(time_)});
        if (probes) {
          std::vector<double> prow{time_};
          const std::vector<double> pp = gas_->probe_pressures();
          prow.insert(prow.end(), pp.begin(), pp.end());
          probes->write_row(prow);
        }
      }
      series.write_row(row);
      if (coll) {
        const CollisionStatistics::Row c = collisions_->take_row(time_, p_.size());
        std::vector<double> crow{time_,
                                 static_cast<double>(c.pair_collisions),
                                 static_cast<double>(c.wall_collisions),
                                 c.frequency,
                                 c.mean_free_time,
                                 c.mean_overlap,
                                 c.max_overlap,
                                 c.mean_duration};
        for (const auto& r : c.regions)
          crow.insert(crow.end(), {r.frequency, r.void_fraction, r.particles});
        coll->write_row(crow);
      }
    }
    if (time_ >= clock_.next_frame - eps || step_ == total) {
      while (clock_.next_frame <= time_ + eps) clock_.next_frame += frame_dt;
      if (!output_order_valid_) { // frames list the particles by id, whatever the store's order
        output_order_.clear();
        if (!std::is_sorted(p_.id.begin(), p_.id.end())) {
          output_order_.resize(p_.size());
          for (std::size_t i = 0; i < p_.size(); ++i)
            output_order_[i] = static_cast<std::uint32_t>(i);
          std::sort(output_order_.begin(), output_order_.end(),
                    [&](std::uint32_t a, std::uint32_t b) { return p_.id[a] < p_.id[b]; });
        }
        output_order_valid_ = true;
      }
      h5.write_frame(step_, time_, p_, output_order_.empty() ? nullptr : &output_order_);
      h5.flush();
      if (fields) {
        gas_->cell_fields(p_, cells);
        auto vec = [](const std::array<std::vector<double>, 3>& v) {
          return std::array<const double*, 3>{v[0].data(), v[1].data(), v[2].data()};
        };
        fields->write_frame(step_, time_, {cells.porosity.data(), cells.pressure.data()},
                            {vec(cells.gas_velocity), vec(cells.solids_velocity)});
      }
      outputs.frame_written(time_);
    }
    if (continuum_due) { // the averages over the interval that ends now
      while (clock_.next_continuum <= time_ + eps) clock_.next_continuum += continuum_interval_;
      const ContinuumFields f = continuum_->result();
      std::vector<const double*> sc{f.solid_fraction.data(), f.granular_temperature.data()};
      for (const auto* tensor : {&f.kinetic_stress, &f.contact_stress, &f.couple_stress})
        for (const auto& component : *tensor) sc.push_back(component.data());
      auto vec = [](const std::array<std::vector<double>, 3>& v) {
        return std::array<const double*, 3>{v[0].data(), v[1].data(), v[2].data()};
      };
      cont->write_frame(step_, time_, sc, {vec(f.velocity), vec(f.angular_vel)});
      outputs.continuum_written(time_);
      continuum_->reset();
    }
    clock_.started = true;
    seconds_output += seconds_since(t0);
  };
  auto flush_outputs = [&]() { outputs.flush(); }; // (the CSV writers flush every row)
  RunSummary s;
  // A checkpoint holds a state that passed the stability checks, with its outputs on disk.
  auto checkpoint = [&]() {
    finish_kick(); // (integration time, not output)
    const auto t0 = Clock::now();
    check_stability();
    flush_outputs();
    write_checkpoint(checkpoint_path);
    s.checkpoint = checkpoint_path;
    seconds_output += seconds_since(t0);
  };

  const auto start = Clock::now();
  const long step0 = step_, folded0 = folded_steps_;
  // A continued run's checkpoint was taken after its step's outputs were written: they are in the
  // files already (writing them again would repeat the last row and frame).
  if (!options.resume) write_outputs();
  if (progress) progress({step_, total, time_, spec_.simulation.end_time, p_.size()});
  try {
    check_stability();
    while (step_ < total) {
      step(true); // its second half kick done by the next step, or by check_stability()
      if (step_ % check_every == 0 || stats_.max_overlap_ratio > spec_.contact.max_overlap)
        check_stability();
      write_outputs();
      if (progress && (step_ % progress_every == 0 || step_ == total))
        progress({step_, total, time_, spec_.simulation.end_time, p_.size()});
      if (options.stop && options.stop->load() != 0) {
        s.stopped_by_signal = options.stop->load();
        break;
      }
      if (time_ >= clock_.next_checkpoint - eps && step_ < total) {
        while (clock_.next_checkpoint <= time_ + eps) clock_.next_checkpoint += checkpoint_dt;
        checkpoint();
      }
    }
    checkpoint(); // at the end, or where a signal stopped the run
  } catch (...) {
    outputs.close_quietly(); // what was written is flushed; the error says what went wrong
    throw;
  }
  outputs.close();
  if (coll) write_overlap_histogram(dir.file("collision_overlap.csv"), *collisions_);
  s.steps = step_ - step0;
  s.wall_seconds = seconds_since(start);
  s.particle_steps_per_second = static_cast<double>(s.steps) * static_cast<double>(p_.size()) /
                                std::max(s.wall_seconds, 1e-9);
  s.neighbour_builds = nl_->builds();
  s.spatial_sorts = sorts_;
  s.folded_steps = folded_steps_ - folded0;
  s.seconds_contacts = t_contacts_;
  s.seconds_integration = t_integration_;
  s.seconds_neighbour = t_neighbour_;
  s.seconds_output = seconds_output;
  s.seconds_gas = t_gas_;
  s.seconds_gas_solver = gas_ ? gas_->solver_seconds() : 0.0;
  s.bytes_per_particle =
      p_.size()
          ? (p_.bytes() + nl_->bytes() + nc_.bytes() + (hard_ ? hard_->bytes() : 0)) / p_.size()
          : 0;
  if (hard_) {
    s.collisions = hard_->stats().collisions;
    s.neighbour_builds = hard_->list_builds();
  } else {
    const double n = static_cast<double>(p_.size());
    s.pairs_per_particle = neighbour_pairs_per_particle();
    s.walls_per_particle = n > 0 ? static_cast<double>(nl_->wall_particle.size()) / n : 0.0;
    s.contacts = stats_.n_contacts;
  }
  const Energies e = energies();
  s.energy_drift =
      (e.kinetic + e.rotational + e.potential + stats_.elastic_energy + e_dsp_ - clock_.e0) /
      clock_.escale;
  return s;
}

} // namespace fluidem
