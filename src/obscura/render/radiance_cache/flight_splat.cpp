#include "obscura/render/radiance_cache/flight_splat.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>

#include "obscura/core/check.h"
#include "obscura/core/parallel.h"
#include "obscura/core/shared_ranges.h"
#include "obscura/medium/lattice_walker.h"
#include "obscura/render/radiance_cache/cache_source.h"
#include "obscura/render/radiance_cache/spherical_harmonics.h"

namespace obscura {
namespace {

// Node layers per task, across the lattice's longest axis (a cloud is wider
// than it is tall: the demo's lattice is 153 × 50 × 23 nodes, whose 6 slabs
// of z layers held 945 000 and 34 000 flights); a cell on a slab's edge is
// integrated by both slabs, each keeping its own corners. A slab of whole
// blocks (NodeLattice::kBlock) owns whole runs of slots when processes
// share their sums.
constexpr int kSlabLayers = 8;

// The slabs' axis: the lattice's longest, so that there are as many slabs as
// can be for threads and processes to share.
int slab_axis(const NodeLattice& lattice) {
  const std::array<int, 3>& dims = lattice.dims();
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (dims[a] > dims[axis]) axis = a;
  return axis;
}

// Gauss–Legendre on [0, 1]: three points where σs varies over a cell (the
// hat times σs is of degree 6 along a line), two where it is constant (the
// hat alone is a cubic, which two points integrate exactly).
constexpr double kGaussT[3] = {0.11270166537925831, 0.5, 0.88729833462074169};
constexpr double kGaussW[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
constexpr double kGauss2T[2] = {0.21132486540518711, 0.78867513459481289};
constexpr double kGauss2W[2] = {0.5, 0.5};

// A flight in lattice coordinates, clipped to where the records hold medium.
struct LatticeFlight {
  Vec3 origin, direction;  // node units; per metre along the flight
  double t0 = 0.0, t1 = 0.0;
};

bool to_lattice(const LatticeVolume& volume, const PhotonFlight& f, LatticeFlight& out) {
  const NodeLattice& lattice = volume.lattice();
  out.origin = lattice.to_lattice(f.origin());
  out.direction = lattice.to_lattice_direction(f.dir());
  out.t0 = 0.0;
  out.t1 = f.length_m;
  return volume.domain().intersect(Ray{out.origin, out.direction}, out.t0, out.t1) &&
         out.t1 > out.t0;
}

// Clips the flight to lattice coordinate `axis` in [lo, hi]; false if
// nothing is left.
bool clip_to_layers(LatticeFlight& f, int axis, double lo, double hi) {
  const double o = f.origin[axis], d = f.direction[axis];
  if (d == 0.0) return o >= lo && o <= hi && f.t1 > f.t0;
  double a = (lo - o) / d, b = (hi - o) / d;
  if (a > b) std::swap(a, b);
  f.t0 = std::max(f.t0, a);
  f.t1 = std::min(f.t1, b);
  return f.t1 > f.t0;
}

// The corner slots of a cell (kNoSlot where the lattice holds no block),
// through the first slots of the 8 blocks at offsets (0|1)³ from the
// cell's, kept while the walk stays in one block.
class CellCorners {
 public:
  explicit CellCorners(const NodeLattice& lattice) : lattice_(lattice) {}

  void operator()(const std::array<int, 3>& cell, std::array<std::size_t, 8>& slot) {
    static_assert(NodeLattice::kBlock == 8);  // blocks and offsets by shifts and masks
    constexpr int b = NodeLattice::kBlock;
    const std::array<int, 3> block = {cell[0] >> 3, cell[1] >> 3, cell[2] >> 3};
    if (block != block_) {
      block_ = block;
      const std::array<int, 3>& n = lattice_.block_dims();
      for (int c = 0; c < 8; ++c) {
        const int bx = block[0] + (c & 1), by = block[1] + (c >> 1 & 1),
                  bz = block[2] + (c >> 2 & 1);
        first_[c] = bx < n[0] && by < n[1] && bz < n[2] ? lattice_.block_first_slot(bx, by, bz)
                                                        : NodeLattice::kNoSlot;
      }
    }
    const int lx = cell[0] & 7, ly = cell[1] & 7, lz = cell[2] & 7;
    if (lx < 7 && ly < 7 && lz < 7) {  // all corners in the cell's own block
      const std::size_t s = first_[0] + static_cast<std::size_t>(lx + b * (ly + b * lz));
      slot = {s,         s + 1,         s + b,         s + b + 1,
              s + b * b, s + b * b + 1, s + b * b + b, s + b * b + b + 1};
      if (first_[0] == NodeLattice::kNoSlot) slot.fill(NodeLattice::kNoSlot);
      return;
    }
    for (int c = 0; c < 8; ++c) {
      const int x = lx + (c & 1), y = ly + (c >> 1 & 1), z = lz + (c >> 2 & 1);
      const std::size_t first = first_[(x >> 3) | (y >> 3) << 1 | (z >> 3) << 2];
      slot[c] = first == NodeLattice::kNoSlot
                    ? NodeLattice::kNoSlot
                    : first + static_cast<std::size_t>((x & 7) + b * ((y & 7) + b * (z & 7)));
    }
  }

 private:
  const NodeLattice& lattice_;
  std::array<int, 3> block_{-1, -1, -1};
  std::array<std::size_t, 8> first_{};
};

// One slab's sums while its flights are splatted: floats, kept for the
// slab's own blocks only (one block layer across the slabs' axis) and
// aligned so that a node's harmonics at degree 3 fill one cache line. The
// flush of a node is the splat's commonest memory access; the lattice's
// whole double sums would spill a core's cache. Added to the double sums,
// node by node, when the slab is done.
class SlabSums {
 public:
  SlabSums(const NodeLattice& lattice, int axis, int slab, std::size_t per_slot)
      : per_slot_(per_slot), local_block_(lattice.block_count(), -1) {
    static_assert(kSlabLayers == NodeLattice::kBlock);
    for (std::size_t b = 0; b < lattice.block_count(); ++b)
      if (lattice.block_first_node(b)[axis] == slab * kSlabLayers) {
        local_block_[b] = static_cast<std::int32_t>(blocks_.size());
        blocks_.push_back(b);
      }
    const std::size_t floats = blocks_.size() * NodeLattice::kBlockNodes * per_slot_;
    data_.reset(static_cast<float*>(
        ::operator new[](std::max<std::size_t>(floats, 1) * sizeof(float), kAlignment)));
    std::fill(data_.get(), data_.get() + floats, 0.0f);
  }

  // The sums of `slot`, a node of the slab's layers.
  float* at(std::size_t slot) {
    const std::int32_t b = local_block_[slot / NodeLattice::kBlockNodes];
    return data_.get() + (static_cast<std::size_t>(b) * NodeLattice::kBlockNodes +
                          slot % NodeLattice::kBlockNodes) *
                             per_slot_;
  }

  // Adds them to the lattice's sums (per slot per_slot values).
  void add_to(std::vector<double>& sum) const {
    for (std::size_t i = 0; i < blocks_.size(); ++i) {
      const float* from = data_.get() + i * NodeLattice::kBlockNodes * per_slot_;
      double* to = sum.data() + blocks_[i] * NodeLattice::kBlockNodes * per_slot_;
      for (std::size_t k = 0; k < NodeLattice::kBlockNodes * per_slot_; ++k) to[k] += from[k];
    }
  }

 private:
  static constexpr std::align_val_t kAlignment{64};
  struct Free {
    void operator()(float* p) const { ::operator delete[](p, kAlignment); }
  };
  std::size_t per_slot_;
  std::vector<std::int32_t> local_block_;  // per lattice block: its index here, or −1
  std::vector<std::size_t> blocks_;        // the slab's blocks, in lattice order
  std::unique_ptr<float[], Free> data_;
};

// The sums of each process's slabs' nodes, shared (core/shared_ranges.h):
// afterwards every process holds every slab's sums.
void share_slabs(const NodeLattice& lattice, int axis, int slabs, int count,
                 const ProcessGroup& processes, std::vector<double>& sum) {
  const auto ranks = static_cast<std::size_t>(processes.size());
  const auto n = static_cast<std::size_t>(count);
  // Per process, the runs of consecutive slots of its slabs' nodes.
  std::vector<IndexRanges> ranges(ranks);
  for (std::size_t slot = 0; slot < lattice.slot_count(); ++slot) {
    if (!lattice.slot_inside(slot)) continue;
    const int s = lattice.slot_node(slot)[axis] / kSlabLayers;
    if (s >= slabs) continue;
    IndexRanges& own = ranges[static_cast<std::size_t>(s) % ranks];
    if (!own.empty() && own.back().second == slot * n)
      own.back().second += n;
    else
      own.emplace_back(slot * n, (slot + 1) * n);
  }
  share_ranges(processes, sum,
               [&](int r) -> const IndexRanges& { return ranges[static_cast<std::size_t>(r)]; });
}

// One flight's contributions to the nodes of node layers [n0, n1) along
// `axis` (`f` clipped to the cells whose corners reach them): Count
// harmonics and Peaks sensor directions per node, known at compile time so
// that the per-node loops unroll.
template <int Count, int Peaks>
void splat_flight(const PhotonFlight& flight, const LatticeFlight& f,
                  const std::array<int, 3>& cell_lo, const std::array<int, 3>& cell_hi, int axis,
                  int n0, int n1, const float* scattering, double inv_volume, int sh_degree,
                  const std::vector<Vec3>& peak_views, CellCorners& cell_corners, SlabSums& sums) {
  std::array<double, kMaxShCoefficients> y;
  spherical_harmonics(flight.dir(), y, sh_degree);
  // The harmonics in floats, added to a node four at a time (the flush
  // below is the splat's commonest arithmetic; GCC leaves the plain loop
  // scalar).
  using Float4 = float __attribute__((vector_size(16)));
  std::array<float, Count> y_float;
  for (int l = 0; l < Count; ++l) y_float[l] = static_cast<float>(y[l]);
  LatticeWalker walker(f.origin, f.direction, f.t0, f.t1, 1.0, cell_lo, cell_hi);
  // The forward peak towards each sensor's direction, at the flight's
  // cosine with it (only g changes along the flight).
  std::array<HgBeyondDegree, kMaxPeakViews> beyond;
  for (int v = 0; v < Peaks; ++v)
    beyond[v] = HgBeyondDegree(dot(flight.dir(), peak_views[v]), sh_degree);
  // The corners of the last cell and their ∫ hat σs dt so far (and
  // ∫ hat σs q dt per sensor direction): a node on the face into the next
  // cell carries its sums on, so each node takes the harmonics once per run
  // of cells rather than once per cell.
  std::array<std::size_t, 8> held_slot;
  held_slot.fill(NodeLattice::kNoSlot);
  std::array<double, 8> held{};
  std::array<std::array<double, kMaxPeakViews>, 8> held_peak{};
  std::array<int, 3> held_cell{-2, -2, -2};
  const double scale = flight.power * inv_volume;
  auto flush = [&](int c) {
    const int n = held_cell[axis] + (c >> axis & 1);
    if (held_slot[c] == NodeLattice::kNoSlot || n < n0 || n >= n1 || held[c] == 0.0) return;
    float* acc = sums.at(held_slot[c]);
    const auto wc = static_cast<float>(scale * held[c]);
    for (int q = 0; q < Count / 4; ++q) {
      Float4 a, y4;
      std::memcpy(&a, acc + 4 * q, sizeof a);
      std::memcpy(&y4, y_float.data() + 4 * q, sizeof y4);
      a += wc * y4;
      std::memcpy(acc + 4 * q, &a, sizeof a);
    }
    for (int l = Count / 4 * 4; l < Count; ++l) acc[l] += wc * y_float[l];
    for (int v = 0; v < Peaks; ++v) acc[Count + v] += static_cast<float>(scale * held_peak[c][v]);
  };
  std::array<std::size_t, 8> slot;
  std::array<int, 3> cell;
  // σs (and σs g, for the forward peak's g) at the corners (zero in blocks
  // the lattice does not hold); a step along one axis keeps the shared
  // face's four.
  std::array<double, 8> corner_sigma_s{}, corner_sigma_s_g{};
  auto load_corner = [&](int c) {
    if (slot[c] == NodeLattice::kNoSlot) {
      corner_sigma_s[c] = corner_sigma_s_g[c] = 0.0;
      return;
    }
    const float* r = scattering + slot[c] * 2;
    corner_sigma_s[c] = r[0];
    if constexpr (Peaks > 0) corner_sigma_s_g[c] = r[1];
  };
  double ta, tb;
  while (walker.next(cell, ta, tb)) {
    if (!(tb > ta) || cell[axis] + 1 < n0 || cell[axis] >= n1) continue;
    // One step along one axis (from the side `side` of the held cell), or a
    // jump: the held corners on the shared face become the new cell's.
    int step_axis = -1, steps = 0;
    for (int a = 0; a < 3; ++a)
      if (cell[a] != held_cell[a]) {
        step_axis = a;
        steps += std::abs(cell[a] - held_cell[a]);
      }
    const int side = steps == 1 && cell[step_axis] > held_cell[step_axis] ? 1 : 0;
    cell_corners(cell, slot);
    if (steps == 1) {
      const int bit = 1 << step_axis;
      for (int c = 0; c < 8; ++c)
        if ((c >> step_axis & 1) == side) {
          corner_sigma_s[c ^ bit] = corner_sigma_s[c];
          if constexpr (Peaks > 0) corner_sigma_s_g[c ^ bit] = corner_sigma_s_g[c];
        }
      for (int c = 0; c < 8; ++c)
        if ((c >> step_axis & 1) == side) load_corner(c);
    } else {
      for (int c = 0; c < 8; ++c) load_corner(c);
    }
    bool uniform = true;
    for (int c = 1; c < 8; ++c)
      uniform = uniform && corner_sigma_s[c] == corner_sigma_s[0] &&
                (Peaks == 0 || corner_sigma_s_g[c] == corner_sigma_s_g[0]);
    const int points = uniform ? 2 : 3;
    const double* rule_t = uniform ? kGauss2T : kGaussT;
    const double* rule_w = uniform ? kGauss2W : kGaussW;
    // ∫ hat_c σs dt over the cell's piece for each corner c.
    std::array<double, 8> weight{};
    std::array<std::array<double, kMaxPeakViews>, 8> peak_weight{};
    for (int q = 0; q < points; ++q) {
      const double t = ta + (tb - ta) * rule_t[q];
      double fx[3];
      for (int a = 0; a < 3; ++a)
        fx[a] = std::clamp(f.origin[a] + t * f.direction[a] - cell[a], 0.0, 1.0);
      // The trilinear weights, corner c = x + 2 y + 4 z, as products of the
      // yz pairs and the x pair.
      const double yz[4] = {(1 - fx[1]) * (1 - fx[2]), fx[1] * (1 - fx[2]), (1 - fx[1]) * fx[2],
                            fx[1] * fx[2]};
      std::array<double, 8> w;
      for (int k = 0; k < 4; ++k) {
        w[2 * k] = (1 - fx[0]) * yz[k];
        w[2 * k + 1] = fx[0] * yz[k];
      }
      double sigma_s = corner_sigma_s[0];
      if (!uniform) {
        sigma_s = 0.0;
        for (int c = 0; c < 8; ++c) sigma_s += w[c] * corner_sigma_s[c];
      }
      const double gw = rule_w[q] * (tb - ta) * sigma_s;
      for (int c = 0; c < 8; ++c) weight[c] += gw * w[c];
      if constexpr (Peaks > 0) {
        if (!(sigma_s > 0.0)) continue;
        double sigma_s_g = corner_sigma_s_g[0];
        if (!uniform) {
          sigma_s_g = 0.0;
          for (int c = 0; c < 8; ++c) sigma_s_g += w[c] * corner_sigma_s_g[c];
        }
        const double g = cache_clamped_g(sigma_s_g / sigma_s);
        for (int v = 0; v < Peaks; ++v) {
          const double gq = gw * beyond[v](g);
          for (int c = 0; c < 8; ++c) peak_weight[c][v] += gq * w[c];
        }
      }
    }
    // The held corners on the shared face carry their sums into the new
    // cell's; the others are done.
    if (steps == 1) {
      for (int c = 0; c < 8; ++c)
        if ((c >> step_axis & 1) == side) {
          weight[c ^ (1 << step_axis)] += held[c];
          for (int v = 0; v < Peaks; ++v) peak_weight[c ^ (1 << step_axis)][v] += held_peak[c][v];
        } else {
          flush(c);
        }
    } else {
      for (int c = 0; c < 8; ++c) flush(c);
    }
    held = weight;
    if constexpr (Peaks > 0) held_peak = peak_weight;
    held_slot = slot;
    held_cell = cell;
  }
  for (int c = 0; c < 8; ++c) flush(c);
}

// Calls f(std::integral_constant<int, Count>, std::integral_constant<int,
// Peaks>) for the harmonics' count at `sh_degree` and `peaks` sensor
// directions.
template <class F>
void dispatch_splat(int sh_degree, int peaks, F&& f) {
  auto with_peaks = [&](auto count) {
    switch (peaks) {
      case 0:
        return f(count, std::integral_constant<int, 0>{});
      case 1:
        return f(count, std::integral_constant<int, 1>{});
      default:
        OBSCURA_CHECK(peaks == 2 && kMaxPeakViews == 2);
        return f(count, std::integral_constant<int, 2>{});
    }
  };
  OBSCURA_CHECK(sh_degree >= 0 && sh_degree <= kMaxShDegree);
  return with_sh_count(sh_degree, with_peaks);
}

}  // namespace

void splat_flights(const LatticeVolume& volume, int node, const std::vector<PhotonFlight>& flights,
                   int sh_degree, int threads, std::vector<double>& sum,
                   const ProcessGroup& processes, const std::vector<Vec3>& peak_views,
                   const CellBox* cells) {
  OBSCURA_CHECK(volume.has_medium());
  const NodeLattice& lattice = volume.lattice();
  const CellBox box = cells ? *cells : all_cells(lattice);
  if (cells && box.empty()) return;
  // A flight's part in the box's cells, false if none: clipped with the
  // walker's own arithmetic (clip_to_layers), so the cells inside keep the
  // crossings an unclipped walk gives them.
  const auto in_box = [&](LatticeFlight& f) {
    if (!cells) return true;
    for (int a = 0; a < 3; ++a)
      if (!clip_to_layers(f, a, box.lo[a], box.hi[a] + 1)) return false;
    return true;
  };
  const int count = sh_coefficient_count(sh_degree);
  const int peaks = static_cast<int>(peak_views.size());
  OBSCURA_CHECK(peaks <= kMaxPeakViews);
  const std::size_t per_slot = static_cast<std::size_t>(count + peaks);
  OBSCURA_CHECK(sum.size() == lattice.slot_count() * per_slot);
  const std::array<int, 3>& dims = lattice.dims();
  const int axis = slab_axis(lattice);
  const int slabs = (dims[axis] + kSlabLayers - 1) / kSlabLayers;
  const double h = lattice.spacing_m();
  const double inv_volume = 1.0 / (h * h * h);  // the tent kernel of one spacing, per m³
  // σs and σs g per slot, out of the records (whose other channels and the
  // cache's light would take a cache line per corner read).
  std::vector<float> scattering(2 * lattice.slot_count());
  {
    const float* records = volume.records(node);
    const auto stride = static_cast<std::size_t>(volume.stride());
    for (std::size_t slot = 0; slot < lattice.slot_count(); ++slot) {
      scattering[2 * slot] = records[slot * stride + record::kSigmaS];
      scattering[2 * slot + 1] = records[slot * stride + record::kSigmaSG];
    }
  }

  // This process's slabs: s ≡ rank (mod ranks).
  const auto rank = static_cast<std::size_t>(processes.rank()),
             ranks = static_cast<std::size_t>(processes.size());
  const auto mine = [&](int s) { return static_cast<std::size_t>(s) % ranks == rank; };

  // Which flights reach which slab: the node layers of the cells it crosses,
  // found per fixed chunk of flights in parallel and joined in chunk order
  // (so in stored order, whatever the thread count).
  OBSCURA_CHECK(flights.size() < std::numeric_limits<std::uint32_t>::max());
  constexpr std::size_t kChunk = 1 << 16;
  const std::size_t chunks = (flights.size() + kChunk - 1) / kChunk;
  using Reach = std::vector<std::vector<std::uint32_t>>;  // flight indices per slab
  std::vector<Reach> chunk_reach(chunks, Reach(static_cast<std::size_t>(slabs)));
  parallel_for(chunks, threads, [&](std::size_t k) {
    Reach& r = chunk_reach[k];
    for (std::size_t i = k * kChunk; i < std::min(flights.size(), (k + 1) * kChunk); ++i) {
      LatticeFlight f;
      if (!to_lattice(volume, flights[i], f) || !in_box(f)) continue;
      const double a = f.origin[axis] + f.t0 * f.direction[axis],
                   b = f.origin[axis] + f.t1 * f.direction[axis];
      const int lo = std::clamp(static_cast<int>(std::floor(std::min(a, b))), 0, dims[axis] - 2);
      const int hi =
          std::clamp(static_cast<int>(std::floor(std::max(a, b))), 0, dims[axis] - 2) + 1;
      for (int s = lo / kSlabLayers; s <= std::min(hi / kSlabLayers, slabs - 1); ++s)
        if (mine(s)) r[static_cast<std::size_t>(s)].push_back(static_cast<std::uint32_t>(i));
    }
  });
  Reach reach(static_cast<std::size_t>(slabs));
  for (std::size_t s = 0; s < reach.size(); ++s) {
    std::size_t n = 0;
    for (const Reach& r : chunk_reach) n += r[s].size();
    reach[s].reserve(n);
    for (Reach& r : chunk_reach) {
      reach[s].insert(reach[s].end(), r[s].begin(), r[s].end());
      std::vector<std::uint32_t>().swap(r[s]);
    }
  }

  const std::size_t own = static_cast<std::size_t>(slabs) / ranks +
                          (rank < static_cast<std::size_t>(slabs) % ranks ? 1 : 0);
  dispatch_splat(sh_degree, peaks, [&](auto count_constant, auto peaks_constant) {
    constexpr int kCount = decltype(count_constant)::value,
                  kPeaks = decltype(peaks_constant)::value;
    parallel_for(own, threads, [&](std::size_t task) {
      const std::size_t s = task * ranks + rank;
      // Node layers n0 … n1 − 1 along the slabs' axis.
      const int n0 = static_cast<int>(s) * kSlabLayers, n1 = std::min(n0 + kSlabLayers, dims[axis]);
      CellCorners cell_corners(lattice);
      SlabSums sums(lattice, axis, static_cast<int>(s), per_slot);
      for (const std::uint32_t i : reach[s]) {
        LatticeFlight f;
        to_lattice(volume, flights[i], f);
        // The part of it in the box and in the cells whose corners reach the
        // slab's node layers, cells n0 − 1 … n1 − 1 (the walker must start
        // inside its range).
        const int c0 = std::max(n0 - 1, box.lo[axis]), c1 = std::min(n1 - 1, box.hi[axis]);
        if (c1 < c0 || !in_box(f) || !clip_to_layers(f, axis, c0, c1 + 1)) continue;
        std::array<int, 3> cell_lo = box.lo, cell_hi = box.hi;
        cell_lo[axis] = c0;
        cell_hi[axis] = c1;
        splat_flight<kCount, kPeaks>(flights[i], f, cell_lo, cell_hi, axis, n0, n1,
                                     scattering.data(), inv_volume, sh_degree, peak_views,
                                     cell_corners, sums);
      }
      sums.add_to(sum);  // the slab's own nodes: no other task writes them
    });
  });
  if (ranks > 1) share_slabs(lattice, axis, slabs, static_cast<int>(per_slot), processes, sum);
}

void widen_splat(const NodeLattice& lattice, int r, std::size_t per_slot, int threads,
                 std::vector<double>& sum) {
  OBSCURA_CHECK(r >= 1 && sum.size() == lattice.slot_count() * per_slot);
  if (r == 1) return;
  std::vector<double> in;
  for (int axis = 0; axis < 3; ++axis) {
    in = sum;
    parallel_for(lattice.block_count(), threads, [&](std::size_t block) {
      for (std::size_t slot = block * NodeLattice::kBlockNodes;
           slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
        double* out = sum.data() + slot * per_slot;
        std::fill(out, out + per_slot, 0.0);
        if (!lattice.slot_inside(slot)) continue;
        std::array<int, 3> n = lattice.slot_node(slot);
        const int centre = n[axis];
        for (int k = 1 - r; k < r; ++k) {
          n[axis] = centre + k;
          const std::size_t from_slot = lattice.slot_of(n[0], n[1], n[2]);
          if (from_slot == NodeLattice::kNoSlot) continue;
          const double w = (1.0 - std::abs(k) / static_cast<double>(r)) / r;
          const double* from = in.data() + from_slot * per_slot;
          for (std::size_t c = 0; c < per_slot; ++c) out[c] += w * from[c];
        }
      }
    });
  }
}

}  // namespace obscura
