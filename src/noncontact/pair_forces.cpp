#include "noncontact/pair_forces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/parallel.hpp"
#include "noncontact/kernels/coulomb.hpp"
#include "noncontact/kernels/van_der_waals.hpp"

namespace fluidem {

namespace {

/// The range beyond contact the list must cover: van der Waals to its range; Coulomb (centre
/// distance r_c) to r_c - 2 r_min, which also covers a particle's own image (2 z < r_c).
double reach_of(const NonContactSpec& spec, const ParticleStore& p) {
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0.0;
  for (const double r : p.radius) r_min = std::min(r_min, r), r_max = std::max(r_max, r);
  double reach = 0.0;
  if (spec.van_der_waals) reach = std::max(reach, spec.van_der_waals->range);
  if (spec.electrostatics && p.size() > 0) {
    const double rc = spec.electrostatics->cutoff;
    if (!(rc > 2.0 * r_max))
      throw std::invalid_argument(
          "electrostatics.cutoff = " + std::to_string(rc) +
          " m does not reach past contact: it must exceed the largest particle diameter, " +
          std::to_string(2.0 * r_max) + " m");
    reach = std::max(reach, rc - 2.0 * r_min);
  }
  return reach;
}

} // namespace

ConservativePairForces::ConservativePairForces(const BoxGeometry& box, const NonContactSpec& spec,
                                               const ParticleStore& p, double skin)
    : spec_(spec), box_(box), nl_(box, skin, 0, reach_of(spec, p)) {}

void ConservativePairForces::permute(const std::vector<std::uint32_t>& new_to_old) {
  order_.add(new_to_old);
}

void ConservativePairForces::update(const ParticleStore& p) {
  order_.update(nl_, p);
  if (!rows_.current(nl_)) rows_.build(nl_, p.size());
}

ConservativePairForces::PairTerm ConservativePairForces::pair(const ParticleStore& p, std::size_t i,
                                                              std::size_t j) const {
  const Vec3 d = centre_to_centre(nl_, p, i, j);
  const double r = std::sqrt(norm2(d));
  const double ri = p.radius[i], rj = p.radius[j];
  const double gap = r - ri - rj;
  double f = 0.0; // > 0 repels
  PairTerm t;
  if (const auto& v = spec_.van_der_waals; v && gap < v->range) {
    const auto pf =
        kernels::van_der_waals(v->hamaker, ri * rj / (ri + rj), v->min_separation, v->range, gap);
    f += pf.force, t.potential += pf.potential, t.in_range = true;
  }
  if (const auto& e = spec_.electrostatics) {
    const double qi = p.charge[i], qj = p.charge[j];
    if (qi != 0.0 && qj != 0.0 && r < e->cutoff) {
      const auto pf = kernels::coulomb_shifted(
          kernels::coulomb_constant(qi, qj, e->relative_permittivity), r, e->cutoff);
      f += pf.force, t.potential += pf.potential, t.in_range = true;
    }
    // The images of j in the conducting walls act on i (and those of i on j, the same
    // magnitude): the pair's share of the induced energy, counted once [coulomb.hpp].
    if (qi != 0.0 && qj != 0.0)
      for (int face = 0; face < 6; ++face) {
        if (!e->conducting[face]) continue;
        const int a = face / 2;
        const double plane = face % 2 == 0 ? box_.lo[a] : box_.hi[a];
        const std::array<double, 3> xj{p.x[j], p.y[j], p.z[j]}, xi{p.x[i], p.y[i], p.z[i]};
        Vec3 di;
        for (int b = 0; b < 3; ++b) {
          const double image = b == a ? 2.0 * plane - xj[b] : xj[b];
          di[b] = nl_.min_image(image - xi[b], b);
        }
        const double ri2 = std::sqrt(norm2(di));
        if (!(ri2 < e->cutoff)) continue;
        const auto pf = kernels::coulomb_shifted(
            kernels::coulomb_constant(qi, -qj, e->relative_permittivity), ri2, e->cutoff);
        t.force += di * (-pf.force / ri2);
        t.potential += pf.potential;
        t.in_range = true;
      }
  }
  t.force += d * (-f / r);
  return t;
}

ConservativePairForces::PairTerm ConservativePairForces::wall(const ParticleStore& p, std::size_t i,
                                                              int face) const {
  const WallDistance w = wall_distance(box_, p, i, face);
  const double z = w.centre;
  PairTerm t;
  double pull = 0.0; // towards the wall, N
  if (const auto& v = spec_.van_der_waals; v && v->wall_hamaker) {
    const double gap = z - p.radius[i];
    if (gap < v->range) {
      const auto pf =
          kernels::van_der_waals(*v->wall_hamaker, p.radius[i], v->min_separation, v->range, gap);
      pull -= pf.force, t.potential += pf.potential, t.in_range = true;
    }
  }
  if (const auto& e = spec_.electrostatics; e && e->conducting[face] && p.charge[i] != 0.0) {
    const double q = p.charge[i];
    if (2.0 * z < e->cutoff) {
      const auto pf = kernels::coulomb_shifted(
          kernels::coulomb_constant(q, -q, e->relative_permittivity), 2.0 * z, e->cutoff);
      pull -= pf.force;                  // the image's force on the charge
      t.potential += 0.5 * pf.potential; // half: the image moves with the charge
      t.in_range = true;
    }
  }
  t.force[w.axis] = w.normal[w.axis] * pull;
  return t;
}

ConservativePairForces::PairTerm ConservativePairForces::particle(const ParticleStore& p,
                                                                  std::size_t i) const {
  PairTerm sum;
  for (std::uint32_t k = rows_.begin(i); k < rows_.end(i); ++k) {
    const PairTerm t = pair(p, i, rows_.partner(k));
    if (!t.in_range) continue;
    sum.force += t.force;
    sum.potential += 0.5 * t.potential;
  }
  for (std::uint32_t k = rows_.wall_begin(i); k < rows_.wall_end(i); ++k) {
    const PairTerm t = wall(p, i, nl_.wall_face[k]);
    if (!t.in_range) continue;
    sum.force += t.force;
    sum.potential += t.potential;
  }
  return sum;
}

void ConservativePairForces::compute(const ParticleStore& p, std::array<std::vector<double>, 3>& f,
                                     std::vector<double>& u) {
  update(p);
  const std::size_t n = p.size();
  for (auto& a : f) a.resize(n);
  u.resize(n);
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    const PairTerm t = particle(p, i);
    f[0][i] = t.force.x, f[1][i] = t.force.y, f[2][i] = t.force.z;
    u[i] = t.potential;
  });
}

double shortest_noncontact_period(const NonContactSpec& spec, const ParticleStore& p) {
  double t = std::numeric_limits<double>::infinity();
  if (p.size() == 0) return t;
  double r_min = std::numeric_limits<double>::infinity(), r_max = 0.0, m_min = r_min, q_max = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    r_min = std::min(r_min, p.radius[i]), r_max = std::max(r_max, p.radius[i]);
    if (!p.fixed(i)) m_min = std::min(m_min, p.mass[i]);
    q_max = std::max(q_max, std::abs(p.charge[i]));
  }
  if (!std::isfinite(m_min)) return t; // nothing moves
  // Two of the lightest: m* = m/2; against a wall, m.
  auto period = [&](double k, double m_eff) {
    return k > 0.0 ? std::numbers::pi * std::sqrt(m_eff / k) : t;
  };
  const double m_eff = 0.5 * m_min;
  if (const auto& v = spec.van_der_waals) { // R* = r_max / 2 between two of the largest
    t = std::min(
        t, period(kernels::van_der_waals_stiffness(v->hamaker, 0.5 * r_max, v->min_separation),
                  m_eff));
    if (v->wall_hamaker)
      t = std::min(
          t, period(kernels::van_der_waals_stiffness(*v->wall_hamaker, r_max, v->min_separation),
                    m_min));
  }
  if (const auto& e = spec.electrostatics) {
    const double k = kernels::coulomb_constant(q_max, q_max, e->relative_permittivity);
    t = std::min(t, period(kernels::coulomb_shifted(k, 2.0 * r_min, e->cutoff).stiffness, m_eff));
  }
  return t;
}

} // namespace fluidem
