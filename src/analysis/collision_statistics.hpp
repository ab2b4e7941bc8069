// Collision statistics of a run [Chang08 (Chang, Lin & Liu, "Applicability limit of binary
// collision model in dense particle flow", AIP Conf. Proc.), Table 1]: collision frequency per
// particle, mean free time, and the distribution of overlap extents (maximum overlap of each
// collision / smaller diameter), globally and in named spherical regions.
//
// Soft spheres: fed one ContactRecord per step (contact/contact_record.hpp, filled by the contact
// loop). Contacts are tracked across steps by their particle ids: each step's contacts are sorted
// by (smaller id, larger id) (wall contacts: (id, -1 - face)) and merged with the sorted list of
// ongoing contacts, O(C log C) per step. A collision begins at the first step a contact appears
// and ends at the first step it is gone; its duration is the time between those two steps (the
// number of steps it was seen x dt), its overlap extent the largest overlap seen / the smaller
// diameter (the contact loop samples once per step, so the extent is accurate to the overlap
// change over one step).
//
// Binary or multiple [Chang08 binary-collision paper, Introduction: the binary model needs
// "multiple (larger than two) particle collisions" to be negligible]: a soft-sphere pair collision
// is *multiple* when, at any step of its life, either of its two particles is in another contact
// too (with a third particle or a wall), *binary* otherwise. Counted when the collision ends,
// globally and per region (the region of its contact point when it began).
//
// Hard spheres: collisions are instantaneous; the engine reports each step's pair and wall
// collisions (with their contact points, for the regions). Overlap extents and durations are zero
// by construction and are not accumulated: those outputs stay empty (NaN in the rows).
//
// Collision frequency per particle over an interval of length T with N particles:
//   f = 2 C / (N T),   C = pair collisions begun in the interval
// (each pair collision is a collision of two particles; wall collisions are counted apart and not
// in f). Mean free time tau = 1/f. Chang08 cites [5] for its definition of f (eq. 5); the formula
// is garbled in the source text available to us, so this is the standard kinetic definition, the
// one whose value for an elastic gas is the Enskog rate f = 4 n d^2 g0 sqrt(pi <v_x^2>).
//
// Regions (Chang08, GC and CC cells): a sphere (centre, radius) - a circle in the x-z plane in
// 2-D. Its particles are those whose centre lies inside (minimum image on periodic axes); at every
// step fed, their count and their volume (disc areas in 2-D) are summed. Over an interval:
//   f_region = 2 C_region / (<N_region> T),  C_region = pair collisions begun whose contact point
//              lies inside the region,
//   void fraction = 1 - <V_particles> / V_sphere (Chang08: "the volumetric sum of the particles,
//              for which their centers of mass fall inside the cell, divided by the volume of the
//              cell" is the solid fraction; its complement is the void fraction theta of Table 1).
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/vec3.hpp"
#include "particles/contact_record.hpp" // plain data (header only): no dependency on the contact loop
#include "particles/particle_store.hpp"

namespace fluidem {

struct CollisionRegion {
  std::string name;
  Vec3 centre;         ///< m
  double radius = 0.0; ///< m, > 0
};

/// One collision of a hard-sphere step: particle ids (id_b = -1 - face for a wall) and the
/// contact point.
struct InstantCollision {
  std::int64_t id_a = 0, id_b = -1;
  Vec3 point;
};

class CollisionStatistics {
public:
  struct Settings {
    std::vector<CollisionRegion> regions;
    int dimension = 3;                  ///< 2: discs in the x-z plane (regions are circles)
    std::array<double, 3> box_length{}; ///< m, for the minimum image on periodic axes
    std::array<bool, 3> periodic{};
    int histogram_bins = 200;   ///< overlap-extent histogram on [0, histogram_max)
    double histogram_max = 0.1; ///< extent (overlap / smaller diameter); above: overflow
    bool soft_spheres = false;  ///< contacts last: the rows say which collisions were multiple
  };
  /// `time`: the start of the first interval (the run's current time).
  CollisionStatistics(Settings settings, double time);

  /// Soft spheres: the contacts at the end of the step that ended at `time`.
  void add_step(const ContactRecord& record, const ParticleStore& p, double time);
  /// Soft spheres on the rank-independent engine: the contacts of the step that ended at
  /// `time`, keyed by ids (gathered from the ranks: one entry per contact, any order), and the
  /// particles whose centres lie in a region (their sums are taken in the store's order: id
  /// order gives the same bits on any number of ranks).
  void add_keyed_step(const std::vector<KeyedContact>& contacts, const ParticleStore& in_regions,
                      double time);
  /// Whether x lies in one of the regions (minimum image on periodic axes).
  bool in_a_region(const Vec3& x) const;
  /// Hard spheres: the collisions of the step that ended at `time`.
  void add_instant_step(const std::vector<InstantCollision>& collisions, const ParticleStore& p,
                        double time);

  struct RegionRow {
    double frequency = 0.0;     ///< 1/s per particle in the region
    double void_fraction = 0.0; ///< 1 - mean particle volume / region volume
    double particles = 0.0;     ///< mean number of particles (centres inside)
    long collisions = 0;        ///< pair collisions begun with the contact point inside
    long ended = 0;             ///< pair collisions ended that had begun inside
    long multiple = 0;          ///< of those, the multiple ones (soft spheres)
  };
  /// The statistics of one interval (between two rows).
  struct Row {
    double time = 0.0, length = 0.0; ///< end of the interval and its length T, s
    long pair_collisions = 0;        ///< pair collisions begun in the interval
    long wall_collisions = 0;        ///< wall collisions begun in the interval
    long pair_collisions_ended = 0;
    long multiple_collisions = 0; ///< pair collisions ended that were multiple (soft spheres)
    double frequency = 0.0;       ///< f = 2 C / (N T), 1/s (NaN when T = 0)
    double mean_free_time = 0.0;  ///< 1/f, s (inf when no collision)
    double mean_overlap = 0.0;    ///< mean extent of the pair collisions ended (NaN if none)
    double max_overlap = 0.0;     ///< largest extent of the pair collisions ended (NaN if none)
    double mean_duration = 0.0;   ///< s, of the pair collisions ended (NaN if none)
    std::vector<RegionRow> regions;
  };
  /// Close the interval at `time` (N = p.size()) and start the next one there.
  Row take_row(double time, std::size_t n_particles);

  /// Totals since the start (or since the state a restart restored).
  long pair_collisions() const { return total_.pairs_begun; }
  long wall_collisions() const { return total_.walls_begun; }
  long pair_collisions_ended() const { return total_.pairs_ended; }
  long wall_collisions_ended() const { return total_.walls_ended; }
  long multiple_collisions() const { return total_.pairs_multiple; }
  double mean_overlap() const;  ///< over all pair collisions ended, NaN if none
  double max_overlap() const;   ///< NaN if none
  double mean_duration() const; ///< s, NaN if none
  std::size_t ongoing() const { return ongoing_.size(); }

  /// Overlap-extent histogram of the pair collisions ended: counts of bins [k w, (k+1) w),
  /// w = histogram_max / bins, then one overflow count (extent >= histogram_max).
  const std::vector<std::int64_t>& histogram() const { return hist_; }
  const Settings& settings() const { return s_; }

  /// What a checkpoint keeps: the ongoing contacts and every accumulator, as flat arrays.
  struct State {
    std::vector<std::int64_t> keys;     ///< 3 per ongoing contact: a, b, multiple (0 or 1)
    std::vector<double> ongoing;        ///< 6 per ongoing contact: begin, max overlap, diameter,
                                        ///< the contact point where it began
    std::vector<std::int64_t> counters; ///< interval and total counters, region collisions
    std::vector<double> sums;           ///< interval start, sums, maxima, region sums
    std::vector<std::int64_t> histogram;
  };
  State state() const;
  /// std::runtime_error when the sizes do not fit these settings.
  void restore(const State& s);

private:
  struct Ongoing {
    std::int64_t a, b; ///< a < b for pairs; (id, -1 - face) for walls
    double begin, max_overlap, diameter;
    Vec3 point;            ///< the contact point when it began (for the regions)
    bool multiple = false; ///< a particle of the pair was in another contact at some step
  };
  struct Acc {
    long pairs_begun = 0, walls_begun = 0, pairs_ended = 0, walls_ended = 0, pairs_multiple = 0;
    double sum_extent = 0.0, max_extent = 0.0, sum_duration = 0.0;
  };
  struct RegionAcc {
    long collisions = 0, ended = 0, multiple = 0;
    long samples = 0;
    double sum_count = 0.0, sum_volume = 0.0;
  };
  /// A step's contacts (entries_ and ab_) merged with the ongoing ones: new keys begin, missing
  /// keys end; point(k): the contact point of the record's k-th contact.
  void merge(double time, const std::function<Vec3(std::size_t)>& point);
  void begin(std::int64_t b, const Vec3& point);
  void end(const Ongoing& c, double time);
  void sample_regions(const ParticleStore& p);
  bool inside(const CollisionRegion& r, const Vec3& x) const;

  Settings s_;
  double t0_;
  Acc interval_, total_;
  std::vector<RegionAcc> region_;
  std::vector<Ongoing> ongoing_, merged_;
  /// A step's contacts for merge(): the packed key, the place in the record, the overlap and
  /// the smaller diameter; their keys (a, b) by place in the record.
  struct Entry {
    std::uint64_t key;
    std::uint32_t k;
    double overlap, diameter;
  };
  std::vector<Entry> entries_, entries_tmp_;
  std::vector<std::array<std::int64_t, 2>> ab_;
  std::vector<std::uint32_t> radix_count_;
  /// Contacts per particle id (id - the step's smallest id; 0, 1, or 2 for more) in the step
  /// being merged; all zeros between steps.
  std::vector<std::uint8_t> degree_;
  std::vector<std::int64_t> ids_; ///< the step's particle ids, sorted (ids spread too far apart)
  std::vector<std::int64_t> hist_;
};

} // namespace fluidem
