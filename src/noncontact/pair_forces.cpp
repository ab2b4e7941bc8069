#include "noncontact/pair_forces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "core/nearest_integer.hpp"
#include "core/parallel.hpp"
#include "noncontact/kernels/coulomb.hpp"
#include "noncontact/kernels/van_der_waals.hpp"

namespace fluidem {

namespace {

/// Minimum-image separation along axis a (the neighbour lists' formula).
double min_image(const BoxGeometry& box, double d, int a) {
  if (!box.periodic[a]) return d;
  const double l = box.length(a);
  return d - l * nearest_integer(d / l);
}

} // namespace

double noncontact_reach(const NonContactSpec& spec, const ParticleStore& p) {
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

ConservativePairForces::ConservativePairForces(const BoxGeometry& box, const NonContactSpec& spec,
                                               const ParticleStore& p, double skin)
    : spec_(spec), box_(box), nl_(box, skin, 0, noncontact_reach(spec, p)) {}

void ConservativePairForces::permute(const std::vector<std::uint32_t>& new_to_old) {
  order_.add(new_to_old);
}

void ConservativePairForces::update(const ParticleStore& p) {
  order_.update(nl_, p);
  if (!rows_.current(nl_)) rows_.build(nl_, p.size());
}

NonContactTerm noncontact_pair(const NonContactSpec& spec, const BoxGeometry& box,
                               const ParticleStore& p, std::size_t i, std::size_t j) {
  const Vec3 d{min_image(box, p.x[j] - p.x[i], 0), min_image(box, p.y[j] - p.y[i], 1),
               min_image(box, p.z[j] - p.z[i], 2)};
  const double r = std::sqrt(norm2(d));
  const double ri = p.radius[i], rj = p.radius[j];
  const double gap = r - ri - rj;
  double f = 0.0; // > 0 repels
  NonContactTerm t;
  if (const auto& v = spec.van_der_waals; v && gap < v->range) {
    const auto pf =
        kernels::van_der_waals(v->hamaker, ri * rj / (ri + rj), v->min_separation, v->range, gap);
    f += pf.force, t.potential += pf.potential, t.in_range = true;
  }
  if (const auto& e = spec.electrostatics) {
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
        const double plane = face % 2 == 0 ? box.lo[a] : box.hi[a];
        const std::array<double, 3> xj{p.x[j], p.y[j], p.z[j]}, xi{p.x[i], p.y[i], p.z[i]};
        Vec3 di;
        for (int b = 0; b < 3; ++b) {
          const double image = b == a ? 2.0 * plane - xj[b] : xj[b];
          di[b] = min_image(box, image - xi[b], b);
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

NonContactTerm noncontact_wall(const NonContactSpec& spec, const BoxGeometry& box,
                               const ParticleStore& p, std::size_t i, int face) {
  const WallDistance w = wall_distance(box, p, i, face);
  const double z = w.centre;
  NonContactTerm t;
  double pull = 0.0; // towards the wall, N
  if (const auto& v = spec.van_der_waals; v && v->wall_hamaker) {
    const double gap = z - p.radius[i];
    if (gap < v->range) {
      const auto pf =
          kernels::van_der_waals(*v->wall_hamaker, p.radius[i], v->min_separation, v->range, gap);
      pull -= pf.force, t.potential += pf.potential, t.in_range = true;
    }
  }
  if (const auto& e = spec.electrostatics; e && e->conducting[face] && p.charge[i] != 0.0) {
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

NonContactTerm ConservativePairForces::particle(const ParticleStore& p, std::size_t i) const {
  NonContactTerm sum;
  for (std::uint32_t k = rows_.begin(i); k < rows_.end(i); ++k)
    add_pair_term(sum, noncontact_pair(spec_, box_, p, i, rows_.partner(k)));
  for (std::uint32_t k = rows_.wall_begin(i); k < rows_.wall_end(i); ++k)
    add_wall_term(sum, noncontact_wall(spec_, box_, p, i, nl_.wall_face[k]));
  return sum;
}

void ConservativePairForces::compute(const ParticleStore& p, std::array<std::vector<double>, 3>& f,
                                     std::vector<double>& u) {
  update(p);
  const std::size_t n = p.size();
  for (auto& a : f) a.resize(n);
  u.resize(n);
  parallel_for(n, threaded_particles(n), [&](std::size_t i) {
    const NonContactTerm t = particle(p, i);
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
