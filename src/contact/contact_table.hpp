// Per-run contact coefficients for every species pair and every (species, wall face), built once
// from the case's materials and the chosen sub-models' declarations (contact/models/), outside
// the hot loop.
//
// Mixing for unlike materials: e, mu, beta0 and mu_r of a particle pair are the arithmetic means
// of the two materials (core/material_mixing.hpp); a particle-wall contact uses the wall's e, mu,
// beta0, mu_r and a wall of infinite mass; E* = 1/((1-nu_a^2)/E_a + (1-nu_b^2)/E_b) [Zhu07
// Table 1] (a rigid wall adds no compliance). What else each model takes, and how it mixes, is
// its `mix` function (docs/contact.md, docs/case-file.md).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include "contact/contact_models.hpp"
#include "contact/models/material_pair.hpp"
#include "contact/pair_params.hpp"
#include "core/case_spec.hpp"
#include "core/memory_budget.hpp"

namespace fluidem {

class ContactTable {
public:
  /// Build from the case. Throws InputError (naming the key) for a model that is named but
  /// refused (contact_models::refusal), coefficients its models do not take
  /// (contact_models::check), or materials no soft-sphere contact can take (e = 0).
  /// `with_particles[s]` is false for a species no particle has (empty: every species has some):
  /// it gets no pair coefficients (they are never read), no durations and no say in the time
  /// step.
  explicit ContactTable(const CaseSpec& spec, std::vector<bool> with_particles = {});

  const PairParams& pair(int si, int sj) const { return pp_[si * n_ + sj]; }
  const PairParams& wall(int s, int face) const { return pw_[s * 6 + face]; }
  int species_count() const { return n_; }
  /// Whether species s has coefficients with the other species (the constructor's
  /// with_particles).
  bool has_particles(int s) const { return used_[s]; }
  /// The chosen sub-models (their index in contact/models/model_list.hpp's lists).
  const contact_models::Chosen& models() const { return models_; }
  /// History doubles per contact that the chosen sub-models keep.
  int history_width() const;

  /// The speed of a particle used for impact-speed contact durations (Hertz), m/s (case value
  /// or the automatic one: free fall over the domain height plus the fastest insertion speed, at
  /// least 0.1 m/s).
  double characteristic_velocity() const { return v_char_; }
  /// The impact speed of a contact duration, m/s: a particle at the characteristic velocity
  /// hits a wall at that speed, and two such particles meet head-on at twice it.
  double impact_speed(bool wall) const { return wall ? v_char_ : 2.0 * v_char_; }

  /// Duration of the normal force pulse of a head-on impact, s (the normal model's).
  double contact_duration(double m_eff, double r_eff, const PairParams& p, bool wall) const;
  /// Shortest contact duration over the species pairs and walls that can meet, s.
  double shortest_contact_duration() const { return t_contact_min_; }
  /// The overlap of a contact with these coefficients under a static force f (N), m.
  double overlap_under(double f, double r_eff, const PairParams& p) const;

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

  /// An input of a contact's duration that the normal model declares (a coefficient with a usual
  /// range, or the Young's modulus of the softer material when it takes elastic constants), and
  /// the contact's coefficients as a function of its value (the time-step rule,
  /// integrate/contact_time_limit.hpp).
  struct DurationInput {
    std::string key, unit;
    double value = 0.0;
    double usual_lo = 0.0, usual_hi = 0.0; ///< the range met in practice
    double usual_value = 0.0;              ///< the value compared with it (E* for a modulus)
    bool longer_when_larger = false;
    std::function<PairParams(double)> params;
  };
  std::vector<DurationInput> duration_inputs(const CaseSpec& spec, const DurationRow& row) const;

  /// The largest overlap below zero at which an attached contact still holds (an adhesive
  /// normal model: JKR's delta_c; 0 for the others) for particles of radius r_max at most
  /// (R* <= r_max), m: the contact neighbour list's reach.
  double attached_reach(double r_max) const;

  /// The memory of the table for the case's species, bytes: every species pair has its
  /// coefficients (the contact loop indexes them by species), so it grows with the square of
  /// the species count.
  static MemoryShare memory_share(const CaseSpec& spec);

private:
  /// The coefficients of one pair (wall: b is the wall's material) with the normal model's
  /// coefficients `normal`; InputError at `key` for e = 0.
  PairParams mix(const CaseSpec& spec, const MaterialSpec& a, const MaterialSpec& b, bool wall,
                 const std::string& key, const contact_models::Coefficients& normal) const;

  int n_ = 0;
  contact_models::Chosen models_;
  ContactSpec contact_; ///< the case's [contact] (the models' coefficients)
  double v_char_ = 1.0;
  double t_contact_min_ = 0.0;
  std::vector<PairParams> pp_, pw_;
  std::vector<bool> used_;
  std::vector<DurationRow> rows_;
};

} // namespace fluidem
