// Per-run contact coefficients for every species pair and every (species, wall face), built once
// from the case's materials with the mixing rules below, outside the hot loop.
//
// Mixing for unlike materials: E* = 1/((1-nu_a^2)/E_a + (1-nu_b^2)/E_b) [Zhu07 Table 1],
// G* = 1/((2-nu_a)/G_a + (2-nu_b)/G_b) with G given or E/(2(1+nu)) [Zhu07 Table 1; Chang08
// eq. 2.16; Di Renzo & Di Maio 2004]; a rigid wall (E = inf) adds no compliance, so E* and G*
// are the particle's own. e, mu, beta0 and mu_r of a particle pair are the arithmetic means of
// the two materials. A particle-wall contact uses the wall's e, mu, beta0, mu_r and a wall of
// infinite mass. Which keys each normal model takes: docs/case-file.md, docs/contact.md.
#pragma once
#include <string>
#include <vector>

#include "core/case_spec.hpp"
#include "core/memory_budget.hpp"

namespace fluidem {

struct PairParams {
  double kn = 0;                 ///< linear: k_n, N/m; Hertz: 4/3 E*, Pa (K = kn sqrt(R*))
  double normal_damping = 0;     ///< linear: eta_n / sqrt(m* k_n); Hertz: Tsuji's alpha
  double kt = 0;                 ///< linear: k_t, N/m; Hertz: c_t, Pa (k_t = c_t sqrt(R* delta))
  double tangential_damping = 0; ///< factor of [Deen07 eq. 30] from beta0
  double tangential_root = 0;    ///< sqrt(2 kt / (7 kn)): eta_t from the normal damping scale
  double mu = 0;                 ///< Coulomb friction (inf: never sliding)
  double mu_r = 0;               ///< rolling friction, dimensionless
  double rolling_damping = 0;    ///< factor of [Deen07 eq. 27] from e (rolling spring-dashpot)
  double restitution = 0;        ///< e_n (for reports)
  double e_star = 0;             ///< effective Young's modulus, Pa (reports)
};

class ContactTable {
public:
  /// Build from the case. Throws InputError (naming the key) for a model that is named but
  /// not implemented, or parameters the model cannot accept (e = 0; contact.stiffness_ratio
  /// with Hertz). `with_particles[s]` is false for a species no particle has (empty: every
  /// species has some): it gets no pair coefficients (they are never read), no durations and no
  /// say in the time step.
  explicit ContactTable(const CaseSpec& spec, std::vector<bool> with_particles = {});

  const PairParams& pair(int si, int sj) const { return pp_[si * n_ + sj]; }
  const PairParams& wall(int s, int face) const { return pw_[s * 6 + face]; }
  int species_count() const { return n_; }
  /// Whether species s has coefficients with the other species (the constructor's
  /// with_particles).
  bool has_particles(int s) const { return used_[s]; }
  NormalModel normal() const { return normal_; }
  TangentialModel tangential() const { return tangential_; }
  RollingModel rolling() const { return rolling_; }

  /// The speed of a particle used for Hertz contact durations, m/s (case value or the automatic
  /// one: free fall over the domain height plus the fastest insertion speed, at least 0.1 m/s).
  double characteristic_velocity() const { return v_char_; }
  /// The impact speed of a Hertz contact duration, m/s: a particle at the characteristic
  /// velocity hits a wall at that speed, and two such particles meet head-on at twice it.
  double impact_speed(bool wall) const { return wall ? v_char_ : 2.0 * v_char_; }

  /// Duration of the normal force pulse of a head-on impact, s (contact/kernels/
  /// normal_damping.hpp); Hertz at impact_speed(wall).
  double contact_duration(double m_eff, double r_eff, const PairParams& p, bool wall) const;
  /// Shortest contact duration over the species pairs and walls that can meet, s.
  double shortest_contact_duration() const { return t_contact_min_; }

  struct DurationRow {
    std::string pair;  ///< e.g. "glass-glass" or "glass-wall z_lo"
    double duration;   ///< s
    int species_a = 0; ///< the pair's species (indices into CaseSpec::species)
    int species_b = 0; ///< (the same as species_a for a wall)
    int face = -1;     ///< the wall face (0..5), -1 for a particle pair
  };
  /// The contact durations of the pairs that can meet: the species with particles with each
  /// other and with the walls.
  const std::vector<DurationRow>& durations() const { return rows_; }

  /// The memory of the table for the case's species, bytes: every species pair has its
  /// coefficients (the contact loop indexes them by species), so it grows with the square of
  /// the species count.
  static MemoryShare memory_share(const CaseSpec& spec);

private:
  int n_ = 0;
  NormalModel normal_;
  TangentialModel tangential_;
  RollingModel rolling_;
  double v_char_ = 1.0;
  double t_contact_min_ = 0.0;
  std::vector<PairParams> pp_, pw_;
  std::vector<bool> used_;
  std::vector<DurationRow> rows_;
};

} // namespace fluidem
