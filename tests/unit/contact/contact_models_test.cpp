// Contact sub-models as data. Every tests/models/*.toml names one stateless kernel of
// src/contact/kernels and holds cases: inputs, outputs worked out independently (the derivation
// is in the file) and a tolerance. One parametrised test runs each case; adding a model file adds
// its cases (ContactModelFiles.EveryFileLoadsAndPasses also runs whatever is on disk at test time,
// so a file added without re-running the test discovery is still checked).
//
// toml++ is header-only (/usr/include/toml++), so this test needs no link beyond fluidem_contact
// (as tests/unit/coupling/drag_closures_test.cpp).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>
#include <map>
#include <numbers>
#include <optional>
#include <ostream>
#include <set>
#include <stdexcept>
#include <string>
#include <toml++/toml.h>
#include <vector>

#include "contact/contact_models.hpp"
#include "contact/kernels/history_rotation.hpp"
#include "contact/kernels/normal_damping.hpp"
#include "contact/kernels/normal_force.hpp"
#include "contact/kernels/rolling_torque.hpp"
#include "contact/kernels/tangential_force.hpp"
#include "contact/models/model_list.hpp"

namespace fluidem {
namespace {

namespace fs = std::filesystem;

fs::path model_dir() {
  return fs::path(FLUIDEM_SOURCE_DIR) / "tests" / "models";
}

/// What a kernel produced, by the output names used in the model files.
struct Outputs {
  std::map<std::string, double> scalars;
  std::map<std::string, Vec3> vectors;
  std::map<std::string, bool> flags;
};

/// A case's inputs; remembers which keys were read, so that a key no kernel reads (a typo)
/// fails the case instead of being silently ignored.
class Inputs {
public:
  explicit Inputs(const toml::table& t) : t_(t) {}

  double num(const std::string& key) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) throw std::runtime_error("missing input '" + key + "'");
    const auto v = n->value<double>(); // integers are accepted as reals
    if (!v || (!n->is_floating_point() && !n->is_integer()))
      throw std::runtime_error("input '" + key + "' is not a number");
    return *v;
  }

  /// num(key), or `fallback` when the case does not give it.
  double num_or(const std::string& key, double fallback) {
    return t_.contains(key) ? num(key) : fallback;
  }

  Vec3 vec(const std::string& key) {
    used_.insert(key);
    const toml::node* n = t_.get(key);
    if (n == nullptr) throw std::runtime_error("missing input '" + key + "'");
    return to_vec3(*n, "input '" + key + "'");
  }

  /// Keys of the case that are neither inputs the kernel read nor bookkeeping keys.
  std::vector<std::string> unused() const {
    std::vector<std::string> out;
    for (const auto& [k, v] : t_) {
      const std::string key(k.str());
      if (key == "name" || key == "expected" || key == "tolerance") continue;
      if (!used_.contains(key)) out.push_back(key);
    }
    return out;
  }

  static Vec3 to_vec3(const toml::node& n, const std::string& what) {
    const toml::array* a = n.as_array();
    if (a == nullptr || a->size() != 3) throw std::runtime_error(what + " is not 3 numbers");
    Vec3 v;
    for (int i = 0; i < 3; ++i) {
      const auto x = (*a)[static_cast<std::size_t>(i)].value<double>();
      if (!x) throw std::runtime_error(what + " is not 3 numbers");
      v[i] = *x;
    }
    return v;
  }

private:
  const toml::table& t_;
  std::set<std::string> used_;
};

/// Outputs that only some versions of the kernels have (energy bookkeeping). A model file that
/// expects one the kernel does not produce fails with "produces no output".
template <class Result>
void bookkeeping_outputs(const Result& r, Outputs& o) {
  if constexpr (requires { r.nonconservative; }) o.vectors["nonconservative"] = r.nonconservative;
  if constexpr (requires { r.spring_loss; }) o.scalars["spring_loss"] = r.spring_loss;
  if constexpr (requires { r.dissipated; }) o.scalars["dissipated"] = r.dissipated;
}

Outputs normal_outputs(const kernels::NormalResponse& r, double v_n) {
  Outputs o;
  o.scalars["elastic"] = r.elastic;
  o.scalars["damping_coeff"] = r.damping_coeff;
  o.scalars["stiffness"] = r.stiffness;
  o.scalars["energy"] = r.energy;
  // Magnitude pushing the pair apart, floored at zero, and its non-conservative part
  // (normal_force.hpp: the damping force is -eta_n v_n).
  const kernels::NormalForce f = kernels::floored_normal_force(r, v_n);
  o.scalars["normal_force"] = f.magnitude;
  o.scalars["nonconservative"] = f.nonconservative;
  return o;
}

using Kernel = std::function<Outputs(Inputs&)>;

/// The kernels a model file can name (its `kernel` key).
const std::map<std::string, Kernel>& kernel_table() {
  static const std::map<std::string, Kernel> table = {
      {"linear_normal",
       [](Inputs& in) {
         const double f = in.num("damping_factor");
         const double k = in.num("k"), m = in.num("m_eff"), delta = in.num("delta");
         return normal_outputs(kernels::linear_normal(k, f, m, delta), in.num("v_n"));
       }},
      {"restitution_damping_factor",
       [](Inputs& in) {
         Outputs o;
         o.scalars["damping_factor"] = kernels::restitution_damping_factor(in.num("restitution"));
         return o;
       }},
      {"normal_damping",
       [](Inputs& in) {
         const double e = in.num("restitution");
         Outputs o;
         o.scalars["damping_ratio"] = kernels::floored_damping_ratio(e);
         o.scalars["linear_damping_factor"] = kernels::linear_damping_factor(e);
         o.scalars["linear_pulse"] =
             kernels::linear_contact_duration(1.0, 1.0, kernels::linear_damping_factor(e));
         o.scalars["hertz_alpha"] = kernels::hertz_damping_alpha(e);
         return o;
       }},
      {"hertz_impact",
       [](Inputs& in) {
         const kernels::HertzImpact h = kernels::scaled_hertz_impact(in.num("alpha"));
         Outputs o;
         o.scalars["restitution"] = h.restitution;
         o.scalars["duration"] = h.duration;
         o.scalars["max_overlap"] = h.max_overlap;
         return o;
       }},
      {"hertz_normal",
       [](Inputs& in) {
         const double k = in.num("k_n"), r = in.num("r_eff"), alpha = in.num("alpha"),
                      m = in.num("m_eff"), delta = in.num("delta");
         return normal_outputs(kernels::hertz_normal(k, r, alpha, m, delta), in.num("v_n"));
       }},
      {"walton_braun_normal",
       [](Inputs& in) {
         const double k1 = in.num("k1"), ratio = in.num("ratio"), h = in.num("delta_max"),
                      delta = in.num("delta");
         const auto r = kernels::walton_braun_normal(k1, ratio, h, delta);
         Outputs o;
         o.scalars["force"] = r.force;
         o.scalars["stiffness"] = r.stiffness;
         o.scalars["energy"] = r.energy;
         o.scalars["spring_loss"] = r.spring_loss;
         o.scalars["delta_max"] = r.delta_max;
         o.scalars["delta0"] = r.delta0;
         return o;
       }},
      {"jkr_normal",
       [](Inputs& in) {
         const double e_star = in.num("e_star"), w = in.num("w"), r = in.num("r_eff"),
                      m = in.num("m_eff"), delta = in.num("delta");
         const double root = std::sqrt(2.0 * std::numbers::pi * w / e_star);
         const auto nr = kernels::jkr_normal(4.0 / 3.0 * e_star, root, r, m, delta);
         Outputs o;
         o.scalars["contact_radius"] = nr.contact_radius;
         o.scalars["elastic"] = nr.elastic;
         o.scalars["energy"] = nr.energy;
         o.scalars["break_energy"] = kernels::jkr_break_energy(4.0 / 3.0 * e_star, root, r);
         return o;
       }},
      {"tangential_spring",
       [](Inputs& in) {
         Vec3 delta_t = in.vec("delta_t");
         const Vec3 v_t = in.vec("v_t");
         const double k_t = in.num("k_t"), eta_t = in.num("eta_t"), mu = in.num("mu"),
                      fn = in.num("fn_abs"), dt = in.num("dt");
         const auto r = kernels::tangential_spring(delta_t, v_t, k_t, eta_t, mu, fn, dt);
         Outputs o;
         o.vectors["force"] = r.force;
         o.vectors["delta_t"] = delta_t;
         o.scalars["energy"] = r.energy;
         o.flags["sliding"] = r.sliding;
         bookkeeping_outputs(r, o);
         return o;
       }},
      {"mindlin_deresiewicz",
       [](Inputs& in) {
         Vec3 delta_t = in.vec("delta_t");
         const Vec3 v_t = in.vec("v_t");
         const double mu = in.num("mu"), fn = in.num("fn_abs"), dmax = in.num("delta_t_max"),
                      dt = in.num("dt");
         const auto r = kernels::mindlin_deresiewicz(delta_t, v_t, mu, fn, dmax, dt);
         Outputs o;
         o.vectors["force"] = r.force;
         o.vectors["delta_t"] = delta_t;
         o.scalars["energy"] = r.energy;
         o.flags["sliding"] = r.sliding;
         bookkeeping_outputs(r, o);
         return o;
       }},
      {"rolling_constant_torque",
       [](Inputs& in) {
         const Vec3 w = in.vec("w_roll");
         const double mu_r = in.num("mu_r"), r_eff = in.num("r_eff"), fn = in.num("fn_abs"),
                      inv_i = in.num("inv_inertia_sum"), dt = in.num("dt");
         const auto r = kernels::rolling_constant_torque(w, mu_r, r_eff, fn, inv_i, dt);
         Outputs o;
         o.vectors["torque"] = r.torque;
         o.scalars["energy"] = r.energy;
         bookkeeping_outputs(r, o);
         return o;
       }},
      {"rolling_spring_dashpot",
       [](Inputs& in) {
         Vec3 theta = in.vec("theta");
         const Vec3 w = in.vec("w_roll");
         const double k_r = in.num("k_r"), c_r = in.num("c_r"), mu_r = in.num("mu_r"),
                      r_eff = in.num("r_eff"), fn = in.num("fn_abs"), dt = in.num("dt");
         const auto r = kernels::rolling_spring_dashpot(theta, w, k_r, c_r, mu_r, r_eff, fn, dt);
         Outputs o;
         o.vectors["torque"] = r.torque;
         o.vectors["theta"] = theta;
         o.scalars["energy"] = r.energy;
         bookkeeping_outputs(r, o);
         return o;
       }},
      {"history_rotation",
       [](Inputs& in) {
         const Vec3 v = in.vec("v"), n0 = in.vec("n0"), n = in.vec("n");
         Outputs o;
         o.vectors["v"] = kernels::rotate_with_contact(v, n0, n);
         return o;
       }},
  };
  return table;
}

/// A kernel of the table, or "normal_model:NAME": the declared normal model NAME
/// (contact/models/) as the contact loop calls it, from the PairParams fields its `mix` sets
/// (kn, normal_damping, kt) and the contact (r_eff, m_eff, delta, v_n; a model with history also
/// `history`, and gives `history` and `spring_loss`): so a new normal model's reference data
/// needs no code here.
std::optional<Kernel> find_kernel(const std::string& name) {
  if (const auto it = kernel_table().find(name); it != kernel_table().end()) return it->second;
  const std::string prefix = "normal_model:";
  if (!name.starts_with(prefix)) return std::nullopt;
  const auto* model =
      contact_models::find(contact_models::Kind::Normal, name.substr(prefix.size()));
  if (model == nullptr || name.size() == prefix.size() || !model->refusal.empty())
    return std::nullopt;
  const int index = model->index;
  return Kernel([index](Inputs& in) {
    PairParams pp;
    pp.kn = in.num("kn");
    pp.normal_damping = in.num("normal_damping");
    pp.kt = in.num_or("kt", 0.0);
    const double r_eff = in.num("r_eff"), m_eff = in.num("m_eff"), delta = in.num("delta");
    const double v_n = in.num("v_n");
    Outputs o;
    contact_models::with_model(contact_models::NormalModels{}, index, [&]<class M>(M) {
      if constexpr (!contact_models::is_refused<M>()) {
        kernels::NormalResponse r;
        if constexpr (M::history_width > 0) {
          // A model with history: its values before the step as `history` (one number per
          // value; a single one for width 1), after the step as the output `history`.
          static_assert(M::history_width == 1, "history inputs of width 1 only so far");
          double hist[1] = {in.num("history")};
          double loss = 0.0;
          r = M::respond(pp, r_eff, m_eff, delta, hist, loss);
          o = normal_outputs(r, v_n);
          o.scalars["history"] = hist[0];
          o.scalars["spring_loss"] = loss;
        } else {
          r = M::respond(pp, r_eff, m_eff, delta);
          o = normal_outputs(r, v_n);
        }
        o.scalars["tangential_stiffness"] = M::tangential_stiffness(pp, r);
        o.scalars["rolling_stiffness"] = M::rolling_stiffness(pp, r);
      }
    });
    return o;
  });
}

/// One case of one model file (or the reason the file could not be used).
struct ModelCase {
  std::string file;   ///< file name, e.g. "linear_normal.toml"
  std::string kernel; ///< the file's `kernel`
  std::string name;   ///< the case's `name`
  double tolerance = 0.0;
  toml::table table; ///< the [[case]] table
  std::string error; ///< non-empty: the file or case is malformed
};

void PrintTo(const ModelCase& c, std::ostream* os) {
  *os << c.file << " / " << c.name;
}

std::vector<fs::path> model_files() {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(model_dir(), ec))
    if (e.path().extension() == ".toml") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<ModelCase> load_file(const fs::path& path) {
  const std::string file = path.filename().string();
  auto broken = [&](const std::string& why) {
    ModelCase c;
    c.file = file;
    c.name = "file_error";
    c.error = why;
    return std::vector<ModelCase>{c};
  };
  toml::table root;
  try {
    root = toml::parse_file(path.string());
  } catch (const toml::parse_error& e) {
    return broken("TOML syntax error at line " + std::to_string(e.source().begin.line) + ": " +
                  std::string(e.description()));
  }
  for (const auto& [k, v] : root) {
    const std::string key(k.str());
    if (key != "kernel" && key != "tolerance" && key != "case")
      return broken("unknown top-level key '" + key + "' (allowed: kernel, tolerance, case)");
  }
  const auto kernel = root["kernel"].value<std::string>();
  if (!kernel) return broken("missing `kernel = \"...\"`");
  if (!find_kernel(*kernel)) return broken("unknown kernel \"" + *kernel + "\"");
  const auto tol = root["tolerance"].value<double>();
  if (!tol || !(*tol > 0.0)) return broken("missing or non-positive `tolerance`");
  const toml::array* cases = root["case"].as_array();
  if (cases == nullptr || cases->empty()) return broken("no [[case]] tables");

  std::vector<ModelCase> out;
  std::set<std::string> names;
  for (std::size_t i = 0; i < cases->size(); ++i) {
    ModelCase c;
    c.file = file;
    c.kernel = *kernel;
    c.tolerance = *tol;
    c.name = "case_" + std::to_string(i);
    const toml::table* t = (*cases)[i].as_table();
    if (t == nullptr) {
      c.error = "[[case]] " + std::to_string(i) + " is not a table";
    } else {
      c.table = *t;
      if (const auto n = (*t)["name"].value<std::string>())
        c.name = *n;
      else
        c.error = "[[case]] " + std::to_string(i) + " has no name";
      if (const auto ct = (*t)["tolerance"].value<double>()) c.tolerance = *ct;
      if (!names.insert(c.name).second) c.error = "duplicate case name '" + c.name + "'";
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<ModelCase> load_all() {
  std::vector<ModelCase> all;
  for (const auto& f : model_files()) {
    auto cases = load_file(f);
    all.insert(all.end(), cases.begin(), cases.end());
  }
  return all;
}

/// Runs one case; returns the list of mismatches (empty = pass).
std::vector<std::string> check_case(const ModelCase& c) {
  if (!c.error.empty()) return {c.error};
  const toml::table* expected = c.table["expected"].as_table();
  if (expected == nullptr || expected->empty()) return {"no [case.expected] outputs"};

  Inputs in(c.table);
  Outputs got;
  try {
    got = (*find_kernel(c.kernel))(in);
  } catch (const std::exception& e) {
    return {e.what()};
  }
  std::vector<std::string> bad;
  for (const auto& key : in.unused())
    bad.push_back("input '" + key + "' is not read by kernel " + c.kernel);

  const double tol = c.tolerance;
  auto close = [tol](double a, double b, double scale) { return std::abs(a - b) <= tol * scale; };
  for (const auto& [k, node] : *expected) {
    const std::string key(k.str());
    if (node.is_boolean()) {
      const auto it = got.flags.find(key);
      if (it == got.flags.end()) {
        bad.push_back(c.kernel + " produces no boolean output '" + key + "'");
      } else if (it->second != *node.value<bool>()) {
        bad.push_back(key + ": got " + (it->second ? "true" : "false") + ", expected " +
                      (*node.value<bool>() ? "true" : "false"));
      }
    } else if (node.is_array()) {
      const auto it = got.vectors.find(key);
      if (it == got.vectors.end()) {
        bad.push_back(c.kernel + " produces no vector output '" + key + "'");
        continue;
      }
      Vec3 want;
      try {
        want = Inputs::to_vec3(node, "expected '" + key + "'");
      } catch (const std::exception& e) {
        bad.push_back(e.what());
        continue;
      }
      const Vec3 v = it->second;
      const double scale = std::max(norm(v), norm(want));
      if (norm(v - want) > tol * scale) {
        auto str = [](const Vec3& a) {
          return "(" + ::testing::PrintToString(a.x) + ", " + ::testing::PrintToString(a.y) + ", " +
                 ::testing::PrintToString(a.z) + ")";
        };
        bad.push_back(key + ": got " + str(v) + ", expected " + str(want) +
                      " (tolerance relative to the length " + ::testing::PrintToString(tol) + ")");
      }
    } else if (const auto want = node.value<double>(); want && (node.is_number())) {
      const auto it = got.scalars.find(key);
      if (it == got.scalars.end()) {
        bad.push_back(c.kernel + " produces no number output '" + key + "'");
      } else if (!close(it->second, *want, std::max(std::abs(it->second), std::abs(*want)))) {
        bad.push_back(key + ": got " + ::testing::PrintToString(it->second) + ", expected " +
                      ::testing::PrintToString(*want) + " (relative tolerance " +
                      ::testing::PrintToString(tol) + ")");
      }
    } else {
      bad.push_back("expected '" + key + "' is neither a number, 3 numbers nor a boolean");
    }
  }
  return bad;
}

std::string describe(const ModelCase& c, const std::vector<std::string>& bad) {
  std::string s = c.file + " / " + c.name + " (kernel " + c.kernel + "):";
  for (const auto& b : bad) s += "\n  " + b;
  return s;
}

// --- one test per case ----------------------------------------------------------------------

class ContactModel : public ::testing::TestWithParam<ModelCase> {};

TEST_P(ContactModel, MatchesHandComputedValues) {
  const ModelCase& c = GetParam();
  const auto bad = check_case(c);
  EXPECT_TRUE(bad.empty()) << describe(c, bad);
}

std::string case_test_name(const ::testing::TestParamInfo<ModelCase>& info) {
  std::string s = fs::path(info.param.file).stem().string() + "__" + info.param.name;
  for (char& ch : s)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return s;
}

INSTANTIATE_TEST_SUITE_P(Files, ContactModel, ::testing::ValuesIn(load_all()), case_test_name);

// --- the collection as a whole --------------------------------------------------------------

TEST(ContactModelFiles, EveryKernelHasAFile) {
  std::map<std::string, int> files_per_kernel;
  for (const auto& [name, fn] : kernel_table()) files_per_kernel[name] = 0;
  for (const auto& f : model_files()) {
    const auto cases = load_file(f);
    ASSERT_FALSE(cases.empty());
    if (!cases.front().kernel.empty()) ++files_per_kernel[cases.front().kernel];
  }
  for (const auto& [name, n] : files_per_kernel)
    EXPECT_GT(n, 0) << "no tests/models/*.toml file for kernel " << name;
  // The six sub-models of the contact law, the history rotation, the dashpots' calibrations.
  for (const char* f :
       {"linear_normal.toml", "hertz_normal.toml", "tangential_spring_sticking.toml",
        "tangential_spring_sliding.toml", "rolling_constant_torque.toml",
        "rolling_spring_dashpot.toml", "history_rotation.toml", "normal_damping.toml",
        "hertz_impact.toml", "restitution_damping_factor.toml", "walton_braun.toml",
        "normal_model_walton_braun.toml", "mindlin_deresiewicz.toml", "jkr_normal.toml"})
    EXPECT_TRUE(fs::exists(model_dir() / f)) << f;
}

TEST(ContactModelFiles, EveryFileLoadsAndPasses) {
  const auto all = load_all();
  ASSERT_GE(all.size(), 7u) << "model files in " << model_dir();
  for (const auto& c : all) {
    const auto bad = check_case(c);
    EXPECT_TRUE(bad.empty()) << describe(c, bad);
  }
}

TEST(ContactModelFiles, CheckerRejectsWrongValuesAndTypos) {
  // The checker itself: a wrong expected value, an unread input and an output the kernel does
  // not have are each reported.
  ModelCase c;
  c.file = "inline.toml";
  c.kernel = "linear_normal";
  c.name = "inline";
  c.tolerance = 1e-12;
  c.table = toml::parse(R"(
    damping_factor = 0.0
    k = 1000.0
    m_eff = 1e-3
    delta = 1e-3
    v_n = 0.0
    stifness = 3.0
    [expected]
    elastic = 1.0000001
    energy = 5e-4
    bogus = 1.0
  )");
  const auto bad = check_case(c);
  ASSERT_EQ(bad.size(), 3u) << describe(c, bad);
  const std::string all = describe(c, bad);
  EXPECT_NE(all.find("stifness"), std::string::npos) << all;
  EXPECT_NE(all.find("elastic"), std::string::npos) << all;
  EXPECT_NE(all.find("bogus"), std::string::npos) << all;
}

} // namespace
} // namespace fluidem
