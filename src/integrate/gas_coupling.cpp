#include "integrate/gas_coupling.hpp"

#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "core/error.hpp"
#include "coupling/drag/drag_model.hpp"
#include "particles/id_order.hpp"

namespace fluidem {

gas::GasSettings GasCoupling::complete_settings(const CaseSpec& spec) {
  gas::GasSettings s = *spec.gas;
  s.dimension = spec.simulation.dimension;
  for (int d = 0; d < 3; ++d) {
    s.lo[d] = spec.domain.lo[d];
    s.hi[d] = spec.domain.hi[d];
    s.gravity[d] = spec.simulation.gravity[d];
  }
  if (s.dimension == 2) {
    s.depth = spec.domain.hi[1] - spec.domain.lo[1];
    s.cells[1] = 1;
  }
  // A periodic particle axis is a periodic gas axis.
  for (int d = 0; d < 3; ++d)
    if (spec.domain.periodic[d]) {
      s.boundary[2 * d].type = gas::BoundaryType::periodic;
      s.boundary[2 * d + 1].type = gas::BoundaryType::periodic;
    }
  return s;
}

GasCoupling::GasCoupling(const CaseSpec& spec, const ParticleStore& p)
    : probes_(spec.output.probes), settings_(spec.coupling) {
  const gas::GasSettings gs = complete_settings(spec);
  // The closure the case names, checked against the registry at the key's location.
  const coupling::drag::DragModel drag =
      coupling::drag::drag_model_of_case(settings_.drag, spec.where("coupling.drag"));
  settings_.drag = coupling::drag::to_string(drag); // (not given: the default closure's name)
  // Polydisperse closures without a given mean diameter: the Sauter mean of the particles,
  // summed in id order, so that a restart from a store sorted in space gets the same bits.
  if (coupling::drag::needs_mean_diameter(drag) && settings_.d_mean == 0.0) {
    double s3 = 0.0, s2 = 0.0;
    for (const std::uint32_t i : id_order(p)) {
      const double d = 2.0 * p.radius[i];
      s3 += d * d * d;
      s2 += d * d;
    }
    if (s2 > 0.0) settings_.d_mean = s3 / s2 * settings_.drag_diameter_factor; // real particles
  }
  try {
    coupling::validate(settings_, gs);
  } catch (const InputError& e) {
    throw InputError(spec.where("coupling"), "coupling", e.what());
  }
  gas_ = std::make_unique<gas::GasSolver>(gs);
  const auto& g = spec.simulation.gravity;
  for (int d = 0; d < 3; ++d)
    if (std::abs(g[static_cast<std::size_t>(d)]) > std::abs(g[static_cast<std::size_t>(vertical_)]))
      vertical_ = d;
  falls_low_ = g[static_cast<std::size_t>(vertical_)] <= 0.0;
  settings_.particle_force = coupling::particle_force_form(settings_, gs);
  // coupling.smoothing_length: the particles read the smoothed velocity (the adjoint of the
  // source's smoothing) only when the gas receives the source.
  smoother_.configure(*gas_, settings_.smoothing_length,
                      settings_.mode == coupling::CouplingMode::two_way);
  coupling::update_porosity(*gas_, p, settings_);
  smoother_.smooth_porosity(gas_->porosity(), coupling::min_porosity);
  if (settings_.mode == coupling::CouplingMode::one_way) {
    // The gas is solved as in the empty domain: porosity 1 in its own steps (step()).
    empty_porosity_.assign(gas_->porosity().size(), 1.0);
    gas_->porosity().swap(empty_porosity_);
    gas_->sync_old_porosity();
    gas_->porosity().swap(empty_porosity_);
  } else {
    gas_->sync_old_porosity();
  }
  if (settings_.mode == coupling::CouplingMode::frozen) set_frozen_field();
  for (auto& f : force_) f.assign(p.size(), 0.0);

  f_.resize(p.size());
}

GasCoupling::~GasCoupling() = default;

void GasCoupling::step(const ParticleStore& p, double time, double dt) {
  using coupling::CouplingMode;
  const coupling::RankSum* ranks = ranks_ ? &*ranks_ : nullptr;
  coupling::update_porosity(*gas_, p, settings_, porosity_scratch_, ranks);
  smoother_.smooth_porosity(gas_->porosity(), coupling::min_porosity); // (off: returns)
  smoother_.with_smoothed_velocity(                                    // (off: the call alone)
      *gas_, [&] { coupling::compute_particle_forces(*gas_, p, settings_, f_, ranks); });
  if (fluid_) fluid_->begin_step(p, f_);
  if (settings_.mode == CouplingMode::two_way) {
    coupling::deposit_momentum_source(*gas_, p, f_, ranks);
    if (fluid_) fluid_->deposit_reaction(*gas_, p, ranks);
    smoother_.smooth_momentum_source(*gas_);
    if (settings_.hold_gas_at_rest) hold_at_rest(dt);
  }
  if (settings_.mode != CouplingMode::frozen) {
    // One-way: the gas steps with porosity 1 and no source (its source arrays stay zero), the
    // particles keep seeing their own porosity (swapped back after the step).
    const bool one_way = settings_.mode == CouplingMode::one_way;
    if (one_way) gas_->porosity().swap(empty_porosity_);
    const auto t0 = std::chrono::steady_clock::now();
    gas_->step(time, dt);
    gas_->check_courant(time + dt, dt);
    solver_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (one_way) gas_->porosity().swap(empty_porosity_);
  }
  smoother_.with_smoothed_velocity(*gas_, [&] { coupling::update_particle_forces(*gas_, p, f_); });
  const std::size_t n = p.size();
  for (auto& f : force_) f.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    force_[0][i] = f_.drag_x[i] + f_.pres_x[i];
    force_[1][i] = f_.drag_y[i] + f_.pres_y[i];
    force_[2][i] = f_.drag_z[i] + f_.pres_z[i];
  }
  if (fluid_) {
    fluid_->compute(*gas_, p, f_);
    for (std::size_t d = 0; d < 3; ++d)
      for (std::size_t i = 0; i < n; ++i) force_[d][i] += fluid_->force()[d][i];
  }
}

void GasCoupling::set_up_fluid_forces(double flow_dt, std::size_t n, const BodyForceSpec* field) {
  if (settings_.forces.any())
    fluid_ = std::make_unique<FluidForces>(settings_.forces, *gas_, flow_dt, n, field);
}

std::vector<std::string> GasCoupling::fluid_state_names() const {
  std::vector<std::string> names;
  if (fluid_)
    for (const auto& [name, v] : fluid_->state()) names.push_back(name);
  return names;
}

void GasCoupling::set_frozen_field() {
  // u_d(x) = U_d + sum_j G_dj x_j on every face of component d (ghosts included: the stencils
  // near the boundary read them), p(x) = p_0 + rho g . (x - lo) at every cell centre
  // (hydrostatic: -V grad p is the buoyancy -V rho g).
  const gas::GasGrid& g = gas_->grid();
  const auto& U = settings_.frozen_velocity;
  const auto& G = settings_.frozen_gradient;
  const gas::GasSettings& gs = gas_->settings();
  const std::vector<double>& rho = gas_->density();
  std::vector<double>& pr = gas_->pressure();
  for (int k = 0; k < g.padded[2]; ++k)
    for (int j = 0; j < g.padded[1]; ++j)
      for (int i = 0; i < g.padded[0]; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        for (int d = 0; d < 3; ++d) {
          const Vec3 x = g.face_centre(d, i, j, k);
          const auto ud = static_cast<std::size_t>(d);
          gas_->velocity(d)[q] = U[ud] + G[ud][0] * x[0] + G[ud][1] * x[1] + G[ud][2] * x[2];
        }
        const Vec3 c = g.cell_centre(i, j, k);
        double h = 0.0;
        for (int d = 0; d < 3; ++d)
          h += gs.gravity[static_cast<std::size_t>(d)] * (c[d] - g.lo[static_cast<std::size_t>(d)]);
        pr[q] += rho[q] * h;
      }
}

void GasCoupling::hold_at_rest(double dt) {
  // Mean momentum per volume of the gas along a periodic axis d, sum over the solved faces of
  // (eps rho)_face u / number of faces (uniform cells); a uniform force -M/dt on the solved
  // faces (explicit source, per cell volume) takes it out within this step.
  const gas::GasGrid& g = gas_->grid();
  const std::vector<double>& eps = gas_->porosity();
  const std::vector<double>& rho = gas_->density();
  for (int d = 0; d < 3; ++d) {
    if (!gas_->boundary().periodic(d)) continue;
    const std::vector<unsigned char>& role = gas_->face_role(d);
    const std::vector<double>& u = gas_->velocity(d);
    const long st = g.stride[static_cast<std::size_t>(d)];
    double m = 0.0;
    long n = 0;
    for (std::size_t q = 0; q < role.size(); ++q) {
      if (role[q] != gas::GasSolver::solved) continue;
      const auto up = static_cast<std::size_t>(static_cast<long>(q) + st);
      m += 0.5 * (eps[q] * rho[q] + eps[up] * rho[up]) * u[q];
      ++n;
    }
    if (n == 0) continue;
    const double f = -m / static_cast<double>(n) / dt;
    std::vector<double>& src = gas_->explicit_source(d);
    for (std::size_t q = 0; q < role.size(); ++q)
      if (role[q] == gas::GasSolver::solved) src[q] += f;
  }
}

double GasCoupling::superficial_velocity(double t) const {
  const gas::GasGrid& g = gas_->grid();
  const gas::BoundaryMap& bc = gas_->boundary();
  double flow = 0.0; // m^3/s into the domain
  for (int side = 0; side < 6; ++side) {
    const int axis = side / 2;
    if (bc.periodic(axis)) continue;
    const int a1 = axis == 0 ? 1 : 0, a2 = axis == 2 ? 1 : 2;
    const double area =
        g.h[static_cast<std::size_t>(a1)] * g.h[static_cast<std::size_t>(a2)]; // one face
    for (int b = 1; b <= g.n[static_cast<std::size_t>(a2)]; ++b)
      for (int a = 1; a <= g.n[static_cast<std::size_t>(a1)]; ++a) {
        std::array<int, 3> c{1, 1, 1};
        c[static_cast<std::size_t>(a1)] = a;
        c[static_cast<std::size_t>(a2)] = b;
        const gas::BoundaryPatch& patch = bc.at(side, c[0], c[1], c[2]);
        if (patch.normal == gas::NormalRule::inflow)
          flow += gas::inflow_velocity(patch.inflow, t) * area;
      }
  }
  const int v1 = (vertical_ + 1) % 3, v2 = (vertical_ + 2) % 3;
  const double cross = g.n[static_cast<std::size_t>(v1)] * g.h[static_cast<std::size_t>(v1)] *
                       g.n[static_cast<std::size_t>(v2)] * g.h[static_cast<std::size_t>(v2)];
  return flow / cross;
}

double GasCoupling::pressure_drop() const {
  const gas::GasGrid& g = gas_->grid();
  const std::vector<double>& pr = gas_->pressure();
  const int axis = vertical_;
  const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
  const int n = g.n[static_cast<std::size_t>(axis)];
  // Mean over a layer of cells normal to `axis` at index k (0 and n + 1: the ghost layers).
  auto layer = [&](int k) {
    double s = 0.0;
    long m = 0;
    for (int b = 1; b <= g.n[static_cast<std::size_t>(a2)]; ++b)
      for (int a = 1; a <= g.n[static_cast<std::size_t>(a1)]; ++a) {
        std::array<int, 3> c{};
        c[static_cast<std::size_t>(axis)] = k;
        c[static_cast<std::size_t>(a1)] = a;
        c[static_cast<std::size_t>(a2)] = b;
        s += pr[static_cast<std::size_t>(g.idx(c[0], c[1], c[2]))];
        ++m;
      }
    return s / static_cast<double>(m);
  };
  // The pressure on a boundary face as the solver sees it: the mean of the ghost cell and the
  // first interior cell (p_1 at an inflow face, the prescribed p_b at a pressure face).
  const double lo = 0.5 * (layer(0) + layer(1)), hi = 0.5 * (layer(n) + layer(n + 1));
  return falls_low_ ? lo - hi : hi - lo;
}

std::vector<double> GasCoupling::probe_pressures() const {
  std::vector<double> v;
  v.reserve(probes_.size());
  for (const ProbeSpec& pr : probes_)
    v.push_back(gas_->pressure_at({pr.position[0], pr.position[1], pr.position[2]}));
  return v;
}

void GasCoupling::cell_fields(const ParticleStore& p, CellFields& out) const {
  const gas::GasGrid& g = gas_->grid();
  const int nx = g.n[0], ny = g.n[1], nz = g.n[2];
  const std::size_t nc = static_cast<std::size_t>(nx) * ny * nz;
  out.cells = g.n;
  out.porosity.assign(nc, 0.0);
  out.pressure.assign(nc, 0.0);
  for (int d = 0; d < 3; ++d) {
    out.gas_velocity[static_cast<std::size_t>(d)].assign(nc, 0.0);
    out.solids_velocity[static_cast<std::size_t>(d)].assign(nc, 0.0);
  }
  auto flat = [&](int i, int j, int k) {
    return static_cast<std::size_t>((i - 1) + nx * ((j - 1) + ny * (k - 1)));
  };
  for (int k = 1; k <= nz; ++k)
    for (int j = 1; j <= ny; ++j)
      for (int i = 1; i <= nx; ++i) {
        const auto q = static_cast<std::size_t>(g.idx(i, j, k));
        const std::size_t c = flat(i, j, k);
        out.porosity[c] = gas_->porosity()[q];
        out.pressure[c] = gas_->pressure()[q];
        for (int d = 0; d < 3; ++d) {
          const auto lowface = static_cast<std::size_t>(static_cast<long>(q) - g.stride[d]);
          const std::vector<double>& u = gas_->velocity(d);
          out.gas_velocity[static_cast<std::size_t>(d)][c] = 0.5 * (u[q] + u[lowface]);
        }
      }
  std::vector<double> mass(nc, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto c = g.cell_of(p.position(i));
    const std::size_t q = flat(c[0], c[1], c[2]);
    mass[q] += p.mass[i];
    out.solids_velocity[0][q] += p.mass[i] * p.vx[i];
    out.solids_velocity[1][q] += p.mass[i] * p.vy[i];
    out.solids_velocity[2][q] += p.mass[i] * p.vz[i];
  }
  for (std::size_t q = 0; q < nc; ++q)
    if (mass[q] > 0.0)
      for (auto& v : out.solids_velocity) v[q] /= mass[q];
}

void GasCoupling::permute(const std::vector<std::uint32_t>& new_to_old) {
  if (fluid_) fluid_->permute(new_to_old);
  for (std::vector<double>& f : force_) {
    if (f.size() != new_to_old.size()) continue; // no flow step yet
    const std::vector<double> old = f;
    for (std::size_t k = 0; k < new_to_old.size(); ++k) f[k] = old[new_to_old[k]];
  }
}

} // namespace fluidem
