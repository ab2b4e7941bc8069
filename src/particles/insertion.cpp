#include "particles/insertion.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <sstream>
#include <unordered_map>

#include <fmt/format.h>

#include "core/input_file.hpp"
#include "core/memory_budget.hpp"
#include "particles/size_distribution.hpp"

namespace fluidem {

namespace {

/// Uniform hash grid over inserted particles for overlap queries during insertion.
class InsertionGrid {
public:
  explicit InsertionGrid(double cell) : cell_(cell) {}
  void add(std::size_t idx, const Vec3& x) { cells_[key(x)].push_back(idx); }
  /// Largest overlap (m) of a sphere (x, r) with the stored particles; also the partner index.
  double max_overlap(const ParticleStore& p, const Vec3& x, double r, std::size_t* who) const {
    double worst = -1e300;
    const long cx = coord(x.x), cy = coord(x.y), cz = coord(x.z);
    for (long dz = -1; dz <= 1; ++dz)
      for (long dy = -1; dy <= 1; ++dy)
        for (long dx = -1; dx <= 1; ++dx) {
          auto it = cells_.find(pack(cx + dx, cy + dy, cz + dz));
          if (it == cells_.end()) continue;
          for (std::size_t j : it->second) {
            const double ov = r + p.radius[j] - norm(x - p.position(j));
            if (ov > worst) {
              worst = ov;
              if (who) *who = j;
            }
          }
        }
    return worst;
  }

private:
  /// Cell coordinate; clamped to +-2^60 so that far-away points cannot overflow (they only
  /// share a cell key, which makes the overlap search do more work, not give a wrong answer).
  long coord(double v) const {
    return static_cast<long>(std::clamp(std::floor(v / cell_), -1.0e18, 1.0e18));
  }
  static std::uint64_t pack(long a, long b, long c) {
    return (static_cast<std::uint64_t>(a & 0x1FFFFF) << 42) |
           (static_cast<std::uint64_t>(b & 0x1FFFFF) << 21) |
           static_cast<std::uint64_t>(c & 0x1FFFFF);
  }
  std::uint64_t key(const Vec3& x) const { return pack(coord(x.x), coord(x.y), coord(x.z)); }
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells_;
};

struct Candidate {
  Vec3 x;
  double r, rho;
  Vec3 v{}, w{}; ///< from the file's Velocities section (zero without one)
};

/// What read_lammps_data found: the particles, and whether the file has a Velocities section.
struct DataFile {
  std::vector<Candidate> atoms;
  bool velocities = false;
};

/// A LAMMPS data file of atom style sphere, as LAMMPS's read_data reads it (docs.lammps.org
/// read_data; fields of AtomVecSphere: "Atoms" id type diameter density x y z [nx ny nz],
/// "Velocities" id vx vy vz wx wy wz): the first line is a title; header lines "N atoms" (others
/// ignored); sections start with a keyword line, Atoms before Velocities, other sections skipped;
/// '#' starts a comment. Velocities: one line per atom, matched by id, w the angular velocity in
/// rad/s (LAMMPS's omega). In 2-D the y velocity and the x and z spins are refused (discs in the
/// x-z plane). Every number finite.
DataFile read_lammps_data(const CaseSpec& spec, const InsertSpec& ins, const std::string& key,
                          double density) {
  if (const auto problem = input_file_problem(ins.file))
    throw InputError(spec.where(key + ".file"), key + ".file", ins.file + " " + *problem);
  std::ifstream in(ins.file);
  const bool two_d = spec.simulation.dimension == 2;
  enum class Section { Header, Atoms, Velocities, Other };
  Section section = Section::Header;
  std::string line;
  long natoms = -1;
  DataFile out;
  std::unordered_map<long, std::size_t> index_of_id; // Atoms id -> index in out.atoms
  std::vector<char> has_velocity;
  long velocity_lines = 0;
  long line_no = 0;
  auto fail = [&](const std::string& what) {
    throw InputError(SourceLocation{ins.file, line_no, 1}, key + ".file", what);
  };
  while (std::getline(in, line)) {
    ++line_no;
    if (line_no == 1) continue; // the title (LAMMPS always skips the first line)
    const auto hash = line.find('#');
    std::istringstream ss(hash == std::string::npos ? line : line.substr(0, hash));
    std::string first;
    if (!(ss >> first)) continue;                             // blank
    if (std::isalpha(static_cast<unsigned char>(first[0]))) { // a section keyword
      if (first == "Atoms") {
        if (!out.atoms.empty()) fail("a second Atoms section");
        section = Section::Atoms;
      } else if (first == "Velocities") {
        if (out.atoms.empty()) fail("the Velocities section must follow the Atoms section");
        if (out.velocities) fail("a second Velocities section");
        if (index_of_id.size() != out.atoms.size())
          fail("the Atoms section repeats an atom id, so the Velocities cannot be matched to "
               "the atoms (allowed: unique ids)");
        out.velocities = true;
        has_velocity.assign(out.atoms.size(), 0);
        section = Section::Velocities;
      } else {
        section = Section::Other;
      }
      continue;
    }
    std::istringstream row(hash == std::string::npos ? line : line.substr(0, hash));
    if (section == Section::Header) {
      long v;
      std::string word;
      if (row >> v >> word && word == "atoms") natoms = v;
    } else if (section == Section::Atoms) {
      long id, type;
      double d, rho, x, y, z;
      if (!(row >> id >> type >> d >> rho >> x >> y >> z) || !std::isfinite(d) ||
          !std::isfinite(rho) || !std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) ||
          d <= 0.0 || rho <= 0.0)
        fail("expected 'id type diameter density x y z' with diameter > 0 and density > 0 "
             "(finite numbers) in the Atoms section");
      index_of_id.emplace(id, out.atoms.size()); // (a repeated id is refused with Velocities)
      out.atoms.push_back({{x, y, z}, 0.5 * d, density > 0.0 ? density : rho});
    } else if (section == Section::Velocities) {
      long id;
      double v[6];
      std::string extra;
      const bool read =
          static_cast<bool>(row >> id >> v[0] >> v[1] >> v[2] >> v[3] >> v[4] >> v[5]);
      if (!read || (row >> extra) ||
          !std::all_of(v, v + 6, [](double c) { return std::isfinite(c); }))
        fail("expected 'id vx vy vz wx wy wz' (atom style sphere: finite numbers, m/s and "
             "rad/s) in the Velocities section");
      if (two_d && (v[1] != 0.0 || v[3] != 0.0 || v[5] != 0.0))
        fail(fmt::format("atom {}: vy = {}, wx = {}, wz = {}; in a 2-D run the discs move in the "
                         "x-z plane and turn about y only (allowed: vy = wx = wz = 0)",
                         id, v[1], v[3], v[5]));
      const auto it = index_of_id.find(id);
      if (it == index_of_id.end()) fail(fmt::format("atom {} is not in the Atoms section", id));
      if (has_velocity[it->second]) fail(fmt::format("atom {} has a second velocity line", id));
      has_velocity[it->second] = 1;
      Candidate& c = out.atoms[it->second];
      c.v = {v[0], v[1], v[2]};
      c.w = {v[3], v[4], v[5]};
      ++velocity_lines;
    }
  }
  if (natoms < 0 || static_cast<long>(out.atoms.size()) != natoms) {
    throw InputError(SourceLocation{ins.file, 0, 0}, key + ".file",
                     fmt::format("LAMMPS data file declares {} atoms but its Atoms section "
                                 "holds {}",
                                 natoms, out.atoms.size()));
  }
  if (out.velocities) {
    if (velocity_lines != natoms)
      throw InputError(SourceLocation{ins.file, 0, 0}, key + ".file",
                       fmt::format("the Velocities section holds {} lines for {} atoms (allowed: "
                                   "one line per atom)",
                                   velocity_lines, natoms));
  }
  return out;
}

/// Refuses at once a random insertion that cannot fit: more particles than random sequential
/// addition places in the region before it jams (docs/case-file.md, [[insert]]). The bound is
/// the jamming fraction of an unbounded space, an area fraction of 0.547069 for discs
/// [Hinrichsen, Feder & Jossang, J. Stat. Phys. 44 (1986) 793] and a volume fraction of 0.384131
/// for spheres [Zhang & Torquato, Phys. Rev. E 88 (2013) 053312], of the region's area
/// (volume), plus one particle per diameter of its edge (d^2 of its surface) for the packing
/// against the edges, which can exceed the bulk fraction in a region a few diameters wide
/// (tools/rsa_limit.py: in no region tried does random addition reach the bound).
void check_random_fill(const CaseSpec& spec, const InsertSpec& ins, const std::string& key,
                       double d, bool two_d) {
  std::vector<double> sides;
  for (int a = 0; a < 3; ++a)
    if (!(two_d && a == 1)) sides.push_back((ins.region_hi[a] - ins.region_lo[a]) / d);
  double size = 1.0, edge = 0.0; // in diameters: area or volume, perimeter or surface
  for (std::size_t a = 0; a < sides.size(); ++a) {
    size *= sides[a];
    edge += two_d ? 2.0 * sides[a] : 2.0 * sides[a] * sides[(a + 1) % 3];
  }
  const double jamming = two_d ? 0.547069 : 0.384131;
  const double particle = two_d ? std::numbers::pi / 4.0 : std::numbers::pi / 6.0; // d = 1
  const double limit = std::floor(jamming * size / particle + edge);
  if (static_cast<double>(ins.count) <= limit) return;
  const double fill = static_cast<double>(ins.count) * particle / size;
  throw InputError(
      spec.where(key + ".count"), key + ".count",
      fmt::format("{} {} of diameter {} m would cover {:.3g}{} the region's {} of {:.3g} {}; "
                  "random insertion jams at {} [{}]: no more than {:.0f} fit in this region (that "
                  "fraction of it, plus one particle per diameter of its edge) (allowed: at most "
                  "{:.0f}; enlarge the region, or use placement = \"lattice\")",
                  ins.count, two_d ? "discs" : "spheres", d, fill, fill > 1.0 ? " times" : " of",
                  two_d ? "area" : "volume", size * (two_d ? d * d : d * d * d),
                  two_d ? "m^2" : "m^3",
                  two_d ? "an area fraction of 0.547" : "a volume fraction of 0.384",
                  two_d ? "Hinrichsen et al. 1986" : "Zhang & Torquato 2013", limit, limit));
}

/// The diameter of equal particles filling the region as the block's do: the species' diameter,
/// or with a size distribution (d^3)^(1/3) over the drawn diameters ((d^2)^(1/2) for discs),
/// which gives the same solids volume (area) for the jamming bound.
double fill_diameter(const std::vector<double>& diameters, double species_diameter, bool two_d) {
  if (diameters.empty()) return species_diameter;
  const double p = two_d ? 2.0 : 3.0;
  double sum = 0.0;
  for (const double d : diameters) sum += std::pow(d, p);
  return std::pow(sum / static_cast<double>(diameters.size()), 1.0 / p);
}

/// The sites of a simple cubic (square) lattice of spacing d between the centres' bounds lo and
/// hi: per axis (m, clamped to 4e9) and in all (clamped to 4e18).
long lattice_sites(const std::array<double, 3>& lo, const std::array<double, 3>& hi, double d,
                   bool two_d, std::array<long, 3>& m) {
  double sites = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double ma = std::floor((hi[a] - lo[a]) / d * (1 + 1e-12)) + 1.0;
    const double axis_sites = (two_d && a == 1) ? 1.0 : ma;
    sites *= axis_sites;
    m[a] = static_cast<long>(std::min(axis_sites, 4.0e9));
  }
  return static_cast<long>(std::min(sites, 4.0e18));
}

/// Every particle inside the domain, and no overlap beyond the tolerance (InputError naming the
/// particles otherwise).
void check_inserted(const CaseSpec& spec, const ParticleStore& store, double dmax) {
  const auto& dom = spec.domain;
  const bool two_d = spec.simulation.dimension == 2;
  // The event-driven engine takes no overlap: it stops at the end of a flow step when two spheres
  // are closer than (1 - 5e-7) of their contact distance (hard_sphere_engine.cpp), and an
  // overlapping pair at the start collides without end ("stalled"). Refused here, where the
  // pair can be named (2.5e-7 of the smaller diameter: at most 5e-7 of any contact distance).
  const bool hard = spec.simulation.engine == Engine::HardSphere;
  const double tol = hard ? 2.5e-7 : spec.simulation.insertion_overlap_tolerance;
  const std::string allowed =
      hard ? std::string("allowed with engine = \"hard_sphere\": none, at most 2.5e-7 of the "
                         "smaller diameter; tools/remove_overlaps.py moves a settled soft-sphere "
                         "bed's spheres apart")
           : fmt::format("allowed: simulation.insertion_overlap_tolerance = {}", tol);
  InsertionGrid check(std::max(dmax, 1e-12));
  for (std::size_t i = 0; i < store.size(); ++i) {
    const Vec3 x = store.position(i);
    const double ri = store.radius[i];
    for (int a = 0; a < 3; ++a) {
      if ((two_d && a == 1) || dom.periodic[a]) continue;
      if (x[a] < dom.lo[a] || x[a] > dom.hi[a]) {
        throw InputError(spec.where("insert"), "insert",
                         fmt::format("particle {} at ({}, {}, {}) m lies outside the domain "
                                     "along {} (allowed: centre in [{}, {}])",
                                     store.id[i], x.x, x.y, x.z, "xyz"[a], dom.lo[a], dom.hi[a]));
      }
      const double wall_overlap = ri - std::min(x[a] - dom.lo[a], dom.hi[a] - x[a]);
      // A fixed particle can never be pushed off a wall (and has no contact with one): it may
      // touch a wall, not cut into it (1e-9 of its diameter: the round-off of a lattice row
      // placed at the wall).
      if (store.fixed(i) && wall_overlap > 1e-9 * 2.0 * ri) {
        throw InputError(spec.where("insert"), "insert",
                         fmt::format("fixed particle {} at ({}, {}, {}) m overlaps the {} wall by "
                                     "{:.3g} of its diameter (allowed: a fixed particle may "
                                     "touch a wall, not overlap it)",
                                     store.id[i], x.x, x.y, x.z,
                                     x[a] - dom.lo[a] < dom.hi[a] - x[a] ? kFaceNames[2 * a]
                                                                         : kFaceNames[2 * a + 1],
                                     wall_overlap / (2.0 * ri)));
      }
      if (wall_overlap > tol * 2.0 * ri) {
        throw InputError(spec.where("insert"), "insert",
                         fmt::format("particle {} at ({}, {}, {}) m overlaps the {} wall by "
                                     "{:.3g} of its diameter at insertion ({})",
                                     store.id[i], x.x, x.y, x.z,
                                     x[a] - dom.lo[a] < dom.hi[a] - x[a] ? kFaceNames[2 * a]
                                                                         : kFaceNames[2 * a + 1],
                                     wall_overlap / (2.0 * ri), allowed));
      }
    }
    std::size_t who = 0;
    const double ov = check.max_overlap(store, x, ri, &who);
    if (ov > tol * 2.0 * std::min(ri, store.radius[who])) {
      throw InputError(spec.where("insert"), "insert",
                       fmt::format("particles {} and {} overlap by {:.3g} of the smaller "
                                   "diameter at insertion ({})",
                                   store.id[who], store.id[i],
                                   ov / (2.0 * std::min(ri, store.radius[who])), allowed));
    }
    check.add(i, x);
  }
}

} // namespace

void insert_particles(const CaseSpec& spec, ParticleStore& store) {
  const auto& dom = spec.domain;
  const bool two_d = spec.simulation.dimension == 2;
  const double y_mid = 0.5 * (dom.lo[1] + dom.hi[1]);
  double dmax = 0.0;
  for (const auto& s : spec.species) dmax = std::max(dmax, s.diameter);
  for (const auto& ins : spec.inserts)
    if (ins.size_distribution)
      dmax = std::max(dmax, SizeDistribution(*ins.size_distribution).largest());
  InsertionGrid grid(std::max(dmax, 1e-12));
  require_memory(spec, {particle_memory_share(spec)});

  for (std::size_t k = 0; k < spec.inserts.size(); ++k) {
    const auto& ins = spec.inserts[k];
    const std::string key = "insert[" + std::to_string(k) + "]";
    const int s = spec.species_index(ins.species);
    if (s < 0) throw InputError(spec.where(key + ".species"), key + ".species", "unknown species");
    const auto& sp = spec.species[s];
    std::mt19937_64 rng(ins.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    // With a size distribution the block's diameters are drawn first, from the block's
    // generator, and placed largest first (random sequential addition fills best that way);
    // without one every particle has the species' diameter and no number is drawn for it.
    std::vector<double> diameters;
    if (ins.size_distribution && ins.placement != Placement::File) {
      diameters =
          SizeDistribution(*ins.size_distribution).sample(static_cast<std::size_t>(ins.count), rng);
      if (ins.placement == Placement::Random)
        std::stable_sort(diameters.begin(), diameters.end(), std::greater<>());
    }
    const auto diameter_of = [&](long c) {
      return diameters.empty() ? sp.diameter : diameters[static_cast<std::size_t>(c)];
    };
    const double d_block =
        diameters.empty() ? sp.diameter : SizeDistribution(*ins.size_distribution).largest();
    const double r = 0.5 * d_block;
    const Vec3 spin{ins.angular_velocity[0], ins.angular_velocity[1], ins.angular_velocity[2]};
    auto velocity = [&]() {
      Vec3 v{ins.velocity[0], ins.velocity[1], ins.velocity[2]};
      if (ins.velocity_spread > 0.0) {
        for (int a = 0; a < 3; ++a) v[a] += ins.velocity_spread * (2.0 * unit(rng) - 1.0);
      }
      if (two_d) v.y = 0.0;
      return v;
    };
    // The bounds of the centres of particles of radius ri in the region.
    const auto centre_bounds = [&](double ri, std::array<double, 3>& lo,
                                   std::array<double, 3>& hi) {
      lo = ins.region_lo, hi = ins.region_hi;
      for (int a = 0; a < 3; ++a) lo[a] += ri, hi[a] -= ri;
      if (two_d) lo[1] = hi[1] = y_mid;
      for (int a = 0; a < 3; ++a) {
        if (hi[a] < lo[a] && hi[a] > lo[a] - 1e-9 * 2.0 * ri) hi[a] = lo[a]; // round-off
        if (hi[a] < lo[a]) {
          throw InputError(spec.where(key + ".region"), key + ".region",
                           fmt::format("the region is narrower than one particle diameter ({} "
                                       "m) along {}",
                                       2.0 * ri, "xyz"[a]));
        }
      }
    };
    std::array<double, 3> lo{}, hi{};
    centre_bounds(r, lo, hi); // the largest particle's

    // A particle with velocity v and angular velocity w (rad/s), or held in place (fixed).
    auto place_moving = [&](const Vec3& x, double radius, double rho, const Vec3& v,
                            const Vec3& w) {
      const std::size_t idx = store.size();
      store.add(x, v, radius, rho, s, static_cast<std::int64_t>(idx + 1));
      store.wx[idx] = w.x, store.wy[idx] = w.y, store.wz[idx] = w.z;
      if (ins.fixed) store.fix(idx);
      store.charge[idx] = ins.charge.value_or(sp.charge);
      grid.add(idx, x);
    };
    auto place = [&](const Vec3& x, double radius, double rho) {
      place_moving(x, radius, rho, velocity(), spin);
    };

    if (ins.placement == Placement::Random) {
      check_random_fill(spec, ins, key, fill_diameter(diameters, sp.diameter, two_d), two_d);
      const long max_attempts = 2000 * ins.count + 100000;
      long placed = 0, attempts = 0;
      double r_placed = r;
      while (placed < ins.count && attempts < max_attempts) {
        ++attempts;
        const double ri = 0.5 * diameter_of(placed);
        if (ri != r_placed) centre_bounds(ri, lo, hi), r_placed = ri;
        Vec3 x{lo[0] + (hi[0] - lo[0]) * unit(rng), lo[1] + (hi[1] - lo[1]) * unit(rng),
               lo[2] + (hi[2] - lo[2]) * unit(rng)};
        if (two_d) x.y = y_mid;
        if (grid.max_overlap(store, x, ri, nullptr) > 0.0) continue;
        place(x, ri, sp.density);
        ++placed;
      }
      if (placed < ins.count) {
        throw InputError(spec.where(key + ".count"), key + ".count",
                         fmt::format("only {} of {} particles of diameter {} m fit in the region "
                                     "by random placement; enlarge the region or use "
                                     "placement = \"lattice\"",
                                     placed, ins.count, diameter_of(placed)));
      }
    } else if (ins.placement == Placement::Lattice) {
      // Simple cubic (square in 2-D) lattice of spacing d, filled x fastest, then y, then z;
      // with a size distribution d is its largest diameter, each particle at a site with its own.
      // Sites per axis and the capacity in double first: a tiny diameter in a large region
      // would overflow the integers (the count is at most 2^31 - 1, so a capacity above that
      // is enough and is clamped).
      std::array<long, 3> m{};
      const long capacity = lattice_sites(lo, hi, d_block, two_d, m);
      if (capacity < ins.count) {
        throw InputError(spec.where(key + ".count"), key + ".count",
                         fmt::format("the region holds at most {} particles of diameter {} m on "
                                     "a lattice, {} requested",
                                     capacity, d_block, ins.count));
      }
      for (long c = 0; c < ins.count; ++c) {
        const long ix = c % m[0], iy = (c / m[0]) % m[1], iz = c / (m[0] * m[1]);
        Vec3 x{lo[0] + static_cast<double>(ix) * d_block, lo[1] + static_cast<double>(iy) * d_block,
               lo[2] + static_cast<double>(iz) * d_block};
        if (two_d) x.y = y_mid;
        place(x, 0.5 * diameter_of(c), sp.density);
      }
    } else {
      const DataFile data = read_lammps_data(spec, ins, key, 0.0);
      // The file's Velocities give each particle its motion: the block's must then be zero
      // (a fixed block reads and checks them, and holds its particles at rest).
      if (data.velocities && !ins.fixed) {
        const auto moving = [](const std::array<double, 3>& v) {
          return v[0] != 0.0 || v[1] != 0.0 || v[2] != 0.0;
        };
        const char* given = moving(ins.velocity)           ? "velocity"
                            : ins.velocity_spread > 0.0    ? "velocity_spread"
                            : moving(ins.angular_velocity) ? "angular_velocity"
                                                           : nullptr;
        if (given)
          throw InputError(spec.where(key + "." + given), key + "." + given,
                           "must be 0 when the data file has a Velocities section (it gives "
                           "each particle's velocity and angular velocity): " +
                               ins.file);
      }
      for (const auto& c : data.atoms) {
        Vec3 x = c.x;
        if (two_d) x.y = y_mid;
        if (data.velocities)
          place_moving(x, c.r, c.rho, c.v, c.w);
        else
          place(x, c.r, c.rho);
      }
    }
  }

  check_inserted(spec, store, dmax);
}

MemoryShare particle_memory_share(const CaseSpec& spec) {
  double requested = 0.0, largest = -1.0;
  std::string key = "insert";
  for (std::size_t k = 0; k < spec.inserts.size(); ++k) {
    const auto& ins = spec.inserts[k];
    if (ins.placement == Placement::File) continue;
    const auto count = static_cast<double>(ins.count);
    requested += count;
    if (count > largest) largest = count, key = "insert[" + std::to_string(k) + "].count";
  }
  return {key, fmt::format("{:.3g} particles", requested), requested * kBytesPerParticle};
}

} // namespace fluidem
