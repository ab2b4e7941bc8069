#include "core/case_spec.hpp"

namespace fluidem {

SourceLocation CaseSpec::where(const std::string& key) const {
  std::string k = key;
  while (!k.empty()) {
    auto it = locations.find(k);
    if (it != locations.end()) return it->second;
    const auto dot = k.find_last_of('.');
    if (dot == std::string::npos) break;
    k.resize(dot);
  }
  return SourceLocation{source_file, 0, 0};
}

int CaseSpec::species_index(const std::string& name) const {
  for (std::size_t i = 0; i < species.size(); ++i)
    if (species[i].name == name) return static_cast<int>(i);
  return -1;
}

const char* to_string(Engine e) {
  return e == Engine::HardSphere ? "hard_sphere" : "soft_sphere";
}

const char* to_string(ContinuumMethod m) {
  return m == ContinuumMethod::Weighted ? "weighted" : "volume";
}

const char* to_string(Placement p) {
  switch (p) {
  case Placement::Random:
    return "random";
  case Placement::Lattice:
    return "lattice";
  case Placement::File:
    return "file";
  }
  return "?";
}

std::vector<double> liquid_fractions(const CaseSpec& spec) {
  std::vector<double> f;
  for (const SpeciesSpec& s : spec.species) f.push_back(s.liquid_fraction);
  return f;
}

} // namespace fluidem
