#include "neighbour/cell_grid.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "core/parallel.hpp"

namespace fluidem {

namespace {
template <class T>
void release_vector(std::vector<T>& v) {
  std::vector<T>().swap(v);
}
} // namespace

void CellGrid::bin(const BoxGeometry& box, double cell_size, const double* x, const double* y,
                   const double* z, std::size_t n, bool threaded) {
  std::array<double, 3> inv_cell{};
  for (int a = 0; a < 3; ++a) {
    const double l = box.length(a);
    const double cells = std::floor(l / cell_size); // (as a double: a huge box does not overflow)
    ncell_[a] =
        cells < 1.0 ? 1 : (cells > kMaxCellsPerAxis ? kMaxCellsPerAxis : static_cast<int>(cells));
    inv_cell[a] = ncell_[a] / l;
  }
  nx_ = static_cast<std::uint64_t>(ncell_[0]);
  ny_ = static_cast<std::uint64_t>(ncell_[1]);
  const std::uint64_t ncells = nx_ * ny_ * static_cast<std::uint64_t>(ncell_[2]); // < 2^61
  dense_ = ncells <= kDenseCellsPerParticle * n + kDenseCellsMin;

  cell_.resize(n);
  const std::array<const double*, 3> pos{x, y, z};
  parallel_for(n, threaded, [&](std::size_t i) {
    std::array<std::uint64_t, 3> c{};
    for (int a = 0; a < 3; ++a) {
      double rel = pos[a][i] - box.lo[a];
      if (box.periodic[a]) rel -= box.length(a) * std::floor(rel / box.length(a));
      c[a] = static_cast<std::uint64_t>(
          std::clamp(static_cast<int>(rel * inv_cell[a]), 0, ncell_[a] - 1));
    }
    cell_[i] = (c[2] * ny_ + c[1]) * nx_ + c[0];
  });

  // Counting sort, stable: the particles of a cell in ascending index order. Each cell's count
  // goes to cell_start_[c], whose running sum is then the end of cell c; the particles are put
  // in from the last, each at --cell_start_[c], which leaves the start of cell c there (no
  // array of cursors: a build allocates as few arrays as before, steady_steps_allocate_nothing).
  cell_particles_.resize(n);
  if (dense_) {
    hash_key_.clear();
    hash_cell_.clear();
    cell_start_.assign(ncells + 1, 0);
    for (std::size_t i = 0; i < n; ++i) ++cell_start_[cell_[i]];
    for (std::size_t c = 1; c < ncells; ++c) cell_start_[c] += cell_start_[c - 1];
    for (std::size_t i = n; i-- > 0;)
      cell_particles_[--cell_start_[cell_[i]]] = static_cast<std::uint32_t>(i);
    cell_start_[ncells] = static_cast<std::uint32_t>(n);
    return;
  }
  // The occupied cells only, numbered in the order of their first particle, through a hash
  // table of at least twice as many slots as particles; then the same counting sort over them.
  const std::uint64_t slots = std::bit_ceil(std::max<std::uint64_t>(2 * n, 2));
  hash_mask_ = slots - 1;
  hash_shift_ = 64 - std::countr_zero(slots);
  hash_key_.assign(slots, kEmptyKey);
  hash_cell_.resize(slots);
  scratch_.resize(n);           // each particle's occupied cell
  cell_start_.assign(n + 1, 0); // (at most n occupied cells)
  std::uint32_t occupied = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t key = cell_[i];
    std::uint64_t s = hash_slot(key);
    while (hash_key_[s] != key && hash_key_[s] != kEmptyKey) s = (s + 1) & hash_mask_;
    if (hash_key_[s] == kEmptyKey) hash_key_[s] = key, hash_cell_[s] = occupied++;
    scratch_[i] = hash_cell_[s];
    ++cell_start_[hash_cell_[s]];
  }
  for (std::uint32_t c = 1; c < occupied; ++c) cell_start_[c] += cell_start_[c - 1];
  for (std::size_t i = n; i-- > 0;)
    cell_particles_[--cell_start_[scratch_[i]]] = static_cast<std::uint32_t>(i);
  cell_start_.resize(static_cast<std::size_t>(occupied) + 1);
  cell_start_[occupied] = static_cast<std::uint32_t>(n);
}

void CellGrid::release() {
  release_vector(cell_);
  release_vector(cell_start_);
  release_vector(cell_particles_);
  release_vector(hash_key_);
  release_vector(hash_cell_);
  release_vector(scratch_);
}

std::size_t CellGrid::bytes() const {
  auto b = [](const auto& v) { return v.capacity() * sizeof(v[0]); };
  return b(cell_) + b(cell_start_) + b(cell_particles_) + b(hash_key_) + b(hash_cell_) +
         b(scratch_);
}

} // namespace fluidem
