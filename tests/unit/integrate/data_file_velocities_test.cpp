// The Velocities section of a LAMMPS data file ([[insert]] placement = "file",
// docs/case-file.md), as LAMMPS's read_data reads atom style sphere (docs.lammps.org/read_data:
// "Velocities" lines are "atom-ID vx vy vz wx wy wz" for sphere, wx wy wz the angular velocity;
// LAMMPS AtomVecSphere::fields_data_vel = {"id", "v", "omega"}): each particle gets the velocity
// and angular velocity of its id, whatever the order of the lines; other sections (Masses) are
// skipped; the title line is skipped. Every malformed file is refused with the file, its line and
// what is allowed: a line of another atom style, an unknown or repeated id, a missing line,
// Velocities before Atoms, non-finite numbers, motion a 2-D run cannot represent (vy, wx, wz),
// and a block velocity given beside the file's. A fixed block reads the section and holds its
// particles at rest.
#include <gtest/gtest.h>

#include <string>

#include "../../common/cli_runner.hpp"
#include "io/case_reader.hpp"
#include "particles/insertion.hpp"

namespace fluidem {
namespace {

/// Bit for bit (Vec3 has no operator==).
bool same(const Vec3& a, const Vec3& b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

using test::TempDir;

const std::string kAtoms = R"(LAMMPS data file via write_data: 3 atoms and Velocities

3 atoms
1 atom types

0 0.04 xlo xhi
0 0.04 ylo yhi
0 0.04 zlo zhi

Masses

1 3.0e-5

Atoms # sphere

7 1 0.004 2700 0.010 0.020 0.010 0 0 0
3 1 0.004 2500 0.020 0.020 0.010 0 0 0
12 1 0.004 2700 0.030 0.020 0.010 0 0 0
)";

const std::string kVelocities = R"(
Velocities

12 0.5 0 -0.25 0 40 0   # a comment
7 -1.5 0 2.0 0 -3.5 0
3 0 0 0 0 0 0
)";

std::string case_text(const std::string& file, int dimension, const std::string& extra = "") {
  return "[simulation]\ndimension = " + std::to_string(dimension) +
         "\nend_time = 0.1\n[domain]\nlo = [0.0, 0.0, 0.0]\nhi = [0.04, 0.04, 0.04]\n"
         "[[species]]\nname = \"s\"\ndiameter = 0.004\ndensity = 2700.0\n"
         "[[insert]]\nspecies = \"s\"\nplacement = \"file\"\nfile = \"" +
         file + "\"\n" + extra;
}

ParticleStore insert(const TempDir& dir, const std::string& data, int dimension = 3,
                     const std::string& extra = "") {
  const auto path = dir.write("bed.data", data);
  const CaseSpec spec = read_case_string(case_text(path.string(), dimension, extra), "c.toml");
  ParticleStore p;
  insert_particles(spec, p);
  return p;
}

TEST(DataFileVelocities, EachParticleGetsItsLine) {
  TempDir dir("fluidem_data");
  const ParticleStore p = insert(dir, kAtoms + kVelocities);
  ASSERT_EQ(p.size(), 3u);
  // Inserted in file order (ids 1..3 here): the file's atoms 7, 3, 12.
  EXPECT_TRUE(same(p.velocity(0), Vec3{-1.5, 0.0, 2.0}));
  EXPECT_TRUE(same(p.angular_velocity(0), Vec3{0.0, -3.5, 0.0}));
  EXPECT_TRUE(same(p.velocity(1), Vec3{0.0, 0.0, 0.0}));
  EXPECT_TRUE(same(p.velocity(2), Vec3{0.5, 0.0, -0.25}));
  EXPECT_TRUE(same(p.angular_velocity(2), Vec3{0.0, 40.0, 0.0}));
  EXPECT_EQ(p.mass[1], sphere_mass(0.002, 2500.0)); // the file's density
  // Without the section: at rest, or the block's velocity and spin.
  const ParticleStore q =
      insert(dir, kAtoms, 3, "velocity = [0.0, 0.0, -1.0]\nangular_velocity = [0.0, 5.0, 0.0]\n");
  EXPECT_TRUE(same(q.velocity(1), Vec3{0.0, 0.0, -1.0}));
  EXPECT_TRUE(same(q.angular_velocity(1), Vec3{0.0, 5.0, 0.0}));
  // 2-D: in-plane motion and spin about y are kept.
  const ParticleStore d = insert(dir, kAtoms + kVelocities, 2);
  EXPECT_TRUE(same(d.angular_velocity(2), Vec3{0.0, 40.0, 0.0}));
  // A fixed block reads the section and holds its particles at rest.
  const ParticleStore f = insert(dir, kAtoms + kVelocities, 3, "fixed = true\n");
  for (std::size_t i = 0; i < f.size(); ++i) {
    EXPECT_TRUE(f.fixed(i));
    EXPECT_TRUE(same(f.velocity(i), Vec3{0.0, 0.0, 0.0}));
    EXPECT_TRUE(same(f.angular_velocity(i), Vec3{0.0, 0.0, 0.0}));
  }
}

std::string error_of(const TempDir& dir, const std::string& data, int dimension = 3,
                     const std::string& extra = "") {
  try {
    (void)insert(dir, data, dimension, extra);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError for:\n" << data;
  return "";
}

TEST(DataFileVelocities, MalformedSectionsAreRefused) {
  TempDir dir("fluidem_data");
  const std::string head = kAtoms + "\nVelocities\n\n";
  const struct {
    std::string data;
    int dimension;
    std::string extra, what;
  } cases[] = {
      {head + "7 -1.5 0 2.0\n3 0 0 0\n12 0 0 0\n", 3, "", "expected 'id vx vy vz wx wy wz'"},
      {head + "7 1 0 0 0 0 0 9\n3 0 0 0 0 0 0\n12 0 0 0 0 0 0\n", 3, "",
       "expected 'id vx vy vz wx wy wz'"},
      {head + "7 0 0 0 0 0 0\n3 0 0 0 0 0 0\n", 3, "", "holds 2 lines for 3 atoms"},
      {head + "7 0 0 0 0 0 0\n3 0 0 0 0 0 0\n5 0 0 0 0 0 0\n", 3, "",
       "atom 5 is not in the Atoms section"},
      {head + "7 0 0 0 0 0 0\n7 0 0 0 0 0 0\n12 0 0 0 0 0 0\n", 3, "",
       "atom 7 has a second velocity line"},
      {head + "7 0 0 0 0 0 0\n3 0 nan 0 0 0 0\n12 0 0 0 0 0 0\n", 3, "",
       "expected 'id vx vy vz wx wy wz'"},
      {head + "7 0 0 0 0 0 0\n3 0 0 1e999 0 0 0\n12 0 0 0 0 0 0\n", 3, "",
       "expected 'id vx vy vz wx wy wz'"},
      {head + "7 0 0.1 0 0 0 0\n3 0 0 0 0 0 0\n12 0 0 0 0 0 0\n", 2, "", "turn about y only"},
      {head + "7 0 0 0 2.0 0 0\n3 0 0 0 0 0 0\n12 0 0 0 0 0 0\n", 2, "", "turn about y only"},
      {"title\n3 atoms\n\nVelocities\n\n7 0 0 0 0 0 0\n" + kAtoms.substr(kAtoms.find("Atoms #")), 3,
       "", "must follow the Atoms section"},
      {kAtoms + kVelocities, 3, "velocity = [0.0, 0.0, -1.0]\n",
       "insert[0].velocity: must be 0 when the data file has a Velocities section"},
      {kAtoms + kVelocities, 3, "angular_velocity = [0.0, 1.0, 0.0]\n",
       "insert[0].angular_velocity: must be 0 when the data file"},
      {kAtoms + "\nAtoms\n\n8 1 0.004 2700 0.01 0.01 0.03\n", 3, "", "a second Atoms section"},
  };
  for (const auto& c : cases) {
    const std::string msg = error_of(dir, c.data, c.dimension, c.extra);
    EXPECT_NE(msg.find(c.what), std::string::npos) << msg;
    EXPECT_NE(msg.find("bed.data"), std::string::npos) << msg; // names the file
  }
  // A repeated id in Atoms cannot be matched.
  std::string twice = kAtoms;
  twice.replace(twice.find("12 1"), 2, "07");
  const std::string msg = error_of(dir, twice + kVelocities);
  EXPECT_NE(msg.find("repeats an atom id"), std::string::npos) << msg;
}

} // namespace
} // namespace fluidem
