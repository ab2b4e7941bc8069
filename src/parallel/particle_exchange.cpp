#include "parallel/particle_exchange.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <type_traits>

namespace fluidem {

namespace {

template <class T>
void put(std::vector<char>& b, const T& v) {
  const std::size_t at = b.size();
  b.resize(at + sizeof(T));
  std::memcpy(b.data() + at, &v, sizeof(T));
}

template <class T>
T take(const std::vector<char>& b, std::size_t& at) {
  if (at + sizeof(T) > b.size()) throw std::logic_error("ParticleExchange: a short message");
  T v;
  std::memcpy(&v, b.data() + at, sizeof(T));
  at += sizeof(T);
  return v;
}

/// A particle's record: everything the store keeps of it.
void put_particle(std::vector<char>& b, const ParticleStore& p, std::size_t i) {
  p.for_each_array([&](const auto& a) { put(b, a[i]); });
}

void take_particle(const std::vector<char>& b, std::size_t& at, ParticleStore& p) {
  p.for_each_array(
      [&](auto& a) { a.push_back(take<typename std::decay_t<decltype(a)>::value_type>(b, at)); });
}

/// Keeps particles `stay` (ascending) of p, kept and extra.
void keep_only(ParticleStore& p, std::span<KeptHistory* const> kept, std::vector<double>& extra,
               int width, const std::vector<std::uint32_t>& stay) {
  p.permute(stay);
  p.resize(stay.size());
  for (KeptHistory* h : kept)
    if (!h->offset.empty()) *h = reorder(*h, stay);
  const auto w = static_cast<std::size_t>(width);
  std::vector<double> e;
  e.reserve(stay.size() * w);
  for (const std::uint32_t i : stay)
    e.insert(e.end(), extra.begin() + static_cast<std::ptrdiff_t>(i * w),
             extra.begin() + static_cast<std::ptrdiff_t>((i + 1) * w));
  extra = std::move(e);
}

} // namespace

std::vector<char> pack_particles(const ParticleStore& p, std::size_t n,
                                 std::span<const double> extra, int width) {
  std::vector<char> b;
  const auto w = static_cast<std::size_t>(width);
  for (std::size_t i = 0; i < n; ++i) {
    put_particle(b, p, i);
    for (std::size_t m = 0; m < w; ++m) put(b, extra[i * w + m]);
  }
  return b;
}

void unpack_particles(const std::vector<char>& bytes, ParticleStore& p, std::vector<double>& extra,
                      int width) {
  std::size_t at = 0;
  while (at < bytes.size()) {
    take_particle(bytes, at, p);
    for (int m = 0; m < width; ++m) extra.push_back(take<double>(bytes, at));
  }
}

std::vector<char> pack_history(const KeptHistory& kept) {
  std::vector<char> b;
  const auto hw = static_cast<std::size_t>(kept.width);
  for (std::size_t i = 0; i < kept.particles(); ++i) {
    put(b, kept.offset[i + 1] - kept.offset[i]);
    for (std::uint32_t m = kept.offset[i]; m < kept.offset[i + 1]; ++m) {
      put(b, kept.key[m]);
      for (std::size_t v = 0; v < hw; ++v) put(b, kept.values[m * hw + v]);
    }
  }
  return b;
}

void unpack_history(const std::vector<char>& bytes, KeptHistory& kept) {
  const auto hw = static_cast<std::size_t>(kept.width);
  if (kept.offset.empty()) kept.offset.push_back(0);
  std::size_t at = 0;
  while (at < bytes.size()) {
    const auto count = take<std::uint32_t>(bytes, at);
    for (std::uint32_t m = 0; m < count; ++m) {
      kept.key.push_back(take<std::int64_t>(bytes, at));
      for (std::size_t v = 0; v < hw; ++v) kept.values.push_back(take<double>(bytes, at));
    }
    kept.offset.push_back(static_cast<std::uint32_t>(kept.key.size()));
  }
}

void ParticleExchange::count_sent() {
  for (const auto& b : out_) bytes_total_ += static_cast<double>(b.size());
  messages_total_ += static_cast<double>(out_.size());
}

ParticleExchange::ParticleExchange(const Communicator& comm, const Decomposition& map, double halo)
    : comm_(comm), map_(map), halo_(halo), neighbours_(map.neighbours(comm.rank(), halo)) {
  if (map.ranks() != comm.size())
    throw std::logic_error("ParticleExchange: the decomposition is not of this run's ranks");
}

std::vector<ParticleTooFar> ParticleExchange::migrate(ParticleStore& p,
                                                      std::span<KeptHistory* const> kept,
                                                      std::vector<double>& extra, int width) {
  const std::size_t n = p.size();
  for (const KeptHistory* h : kept)
    if (!h->offset.empty() && h->particles() != n)
      throw std::logic_error("ParticleExchange::migrate: histories of other particles");
  const auto w = static_cast<std::size_t>(width);
  std::vector<ParticleTooFar> too_far;
  std::vector<std::uint32_t> stay;
  out_.assign(neighbours_.size(), {});
  for (std::size_t i = 0; i < n; ++i) {
    const int to = map_.owner(p.x[i], p.y[i], p.z[i]);
    if (to == comm_.rank()) {
      stay.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    const auto it = std::lower_bound(neighbours_.begin(), neighbours_.end(), to);
    if (it == neighbours_.end() || *it != to) {
      too_far.push_back({p.id[i], p.x[i], p.y[i], p.z[i]});
      stay.push_back(static_cast<std::uint32_t>(i));
      continue;
    }
    std::vector<char>& b = out_[static_cast<std::size_t>(it - neighbours_.begin())];
    put_particle(b, p, i);
    for (std::size_t m = 0; m < w; ++m) put(b, extra[i * w + m]);
    for (const KeptHistory* h : kept) {
      const auto hw = static_cast<std::size_t>(h->width);
      const std::uint32_t h0 = h->offset.empty() ? 0 : h->offset[i];
      const std::uint32_t h1 = h->offset.empty() ? 0 : h->offset[i + 1];
      put(b, h1 - h0);
      for (std::uint32_t m = h0; m < h1; ++m) {
        put(b, h->key[m]);
        for (std::size_t v = 0; v < hw; ++v) put(b, h->values[m * hw + v]);
      }
    }
  }
  keep_only(p, kept, extra, width, stay);
  count_sent();
  const auto in = comm_.exchange(neighbours_, out_, neighbours_);
  for (const std::vector<char>& b : in) {
    std::size_t at = 0;
    while (at < b.size()) {
      take_particle(b, at, p);
      for (std::size_t m = 0; m < w; ++m) extra.push_back(take<double>(b, at));
      for (KeptHistory* h : kept) {
        const auto hw = static_cast<std::size_t>(h->width);
        if (h->offset.empty()) h->offset.push_back(0);
        const auto count = take<std::uint32_t>(b, at);
        for (std::uint32_t m = 0; m < count; ++m) {
          h->key.push_back(take<std::int64_t>(b, at));
          for (std::size_t v = 0; v < hw; ++v) h->values.push_back(take<double>(b, at));
        }
        h->offset.push_back(static_cast<std::uint32_t>(h->key.size()));
      }
    }
  }
  return too_far;
}

void ParticleExchange::fill_ghosts(ParticleStore& p) {
  const std::size_t owned = p.size();
  sent_.assign(neighbours_.size(), {});
  out_.assign(neighbours_.size(), {});
  const double h2 = halo_ * halo_;
  for (std::size_t k = 0; k < neighbours_.size(); ++k)
    for (std::size_t i = 0; i < owned; ++i)
      if (map_.distance2(neighbours_[k], p.x[i], p.y[i], p.z[i]) < h2) {
        sent_[k].push_back(static_cast<std::uint32_t>(i));
        put_particle(out_[k], p, i);
      }
  count_sent();
  const auto in = comm_.exchange(neighbours_, out_, neighbours_);
  received_.assign(in.size(), 0);
  for (std::size_t k = 0; k < in.size(); ++k) {
    std::size_t at = 0;
    const std::size_t before = p.size();
    while (at < in[k].size()) take_particle(in[k], at, p);
    received_[k] = p.size() - before;
  }
}

void ParticleExchange::update_ghosts(ParticleStore& p, std::size_t owned) {
  out_.assign(neighbours_.size(), {});
  for (std::size_t k = 0; k < neighbours_.size(); ++k) {
    out_[k].reserve(sent_[k].size() * 9 * sizeof(double));
    for (const std::uint32_t i : sent_[k])
      for (const double v :
           {p.x[i], p.y[i], p.z[i], p.vx[i], p.vy[i], p.vz[i], p.wx[i], p.wy[i], p.wz[i]})
        put(out_[k], v);
  }
  count_sent();
  const auto in = comm_.exchange(neighbours_, out_, neighbours_);
  std::size_t g = owned;
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (in[k].size() != received_[k] * 9 * sizeof(double))
      throw std::logic_error("ParticleExchange::update_ghosts: the ghosts changed without a fill");
    std::size_t at = 0;
    for (std::size_t m = 0; m < received_[k]; ++m, ++g)
      for (std::vector<double>* a : {&p.x, &p.y, &p.z, &p.vx, &p.vy, &p.vz, &p.wx, &p.wy, &p.wz})
        (*a)[g] = take<double>(in[k], at);
  }
}

void ParticleExchange::update_ghost_values(std::vector<double>& values, std::size_t owned) {
  out_.assign(neighbours_.size(), {});
  for (std::size_t k = 0; k < neighbours_.size(); ++k) {
    out_[k].reserve(sent_[k].size() * sizeof(double));
    for (const std::uint32_t i : sent_[k]) put(out_[k], values[i]);
  }
  count_sent();
  const auto in = comm_.exchange(neighbours_, out_, neighbours_);
  std::size_t g = owned;
  for (std::size_t k = 0; k < in.size(); ++k) {
    if (in[k].size() != received_[k] * sizeof(double))
      throw std::logic_error("ParticleExchange::update_ghost_values: the ghosts changed without "
                             "a fill");
    std::size_t at = 0;
    for (std::size_t m = 0; m < received_[k]; ++m, ++g) values.at(g) = take<double>(in[k], at);
  }
}

} // namespace fluidem
