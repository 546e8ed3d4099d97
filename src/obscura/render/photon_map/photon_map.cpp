#include "obscura/render/photon_map/photon_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <nanoflann.hpp>
#include <string>
#include <utility>

#include "obscura/core/error.h"

namespace obscura {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// nanoflann reads points through this adaptor. Coordinates are handed out as
// double (exact conversions of the stored floats) so the tree's split values,
// the query point and every distance are doubles: the query point is never
// rounded to float.
struct PhotonSource {
  const std::vector<Photon>* photons = nullptr;
  std::size_t kdtree_get_point_count() const { return photons->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t axis) const {
    return static_cast<double>((*photons)[i].position_m[axis]);
  }
  template <class Box>
  bool kdtree_get_bbox(Box&) const {
    return false;  // let nanoflann compute it
  }
};

// The metric nanoflann calls at the leaves. It evaluates photon_distance2_m2,
// so the tree selects by exactly the distance the queries report and the tests
// recompute (nanoflann's L2_Simple_Adaptor would sum in its own order).
// accum_dist is the squared distance along one axis to a splitting plane,
// which nanoflann adds up into a lower bound for pruning.
struct PhotonMetric {
  using ElementType = double;
  using DistanceType = double;
  const PhotonSource& data_source;
  explicit PhotonMetric(const PhotonSource& source) : data_source(source) {}
  double evalMetric(const double* q, std::uint32_t i, std::size_t) const {
    return photon_distance2_m2((*data_source.photons)[i], Vec3{q[0], q[1], q[2]});
  }
  template <class U, class V>
  double accum_dist(U a, V b, std::size_t) const {
    return (a - b) * (a - b);
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<PhotonMetric, PhotonSource, 3, std::uint32_t>;

// (distance², index): ordering these lexicographically is the documented
// result order.
using Entry = std::pair<double, std::uint32_t>;

// The bound handed to nanoflann for pruning, strictly above the largest
// distance² a query still accepts. Two reasons it is above, not equal:
//  * nanoflann passes a leaf photon on only if its distance² is strictly
//    below the bound, and a photon exactly at the accepted limit must reach
//    the collector (ties at the k-th place, photons exactly on the radius);
//  * nanoflann's lower bound for a subtree is updated incrementally
//    (m + cut − old) in double; each update may round up by a few ulps of the
//    terms, which are at most `reach2` (the squared distance from the query to
//    the far corner of the tree's box). Over the tree's depth that is far
//    below 1e-12·reach2, so the slack keeps rounding from pruning a subtree
//    that holds a photon the exact search would accept.
// The collectors themselves accept by exact comparisons, so the slack only
// costs a few extra distance evaluations, never a wrong answer.
double pruning_bound(double accepted_d2, double reach2) {
  if (!(accepted_d2 < kInf)) return kInf;
  return std::nextafter(accepted_d2 + 1e-12 * (accepted_d2 + reach2), kInf);
}

// k nearest with distance² <= r2: a max-heap of the best k (distance², index)
// entries seen so far, so the worst is replaced in O(log k).
class NearestCollector {
 public:
  NearestCollector(std::size_t k, double r2, double reach2, std::vector<Entry>& heap)
      : k_(k), r2_(r2), reach2_(reach2), bound_(pruning_bound(r2, reach2)), heap_(heap) {
    heap_.clear();
  }
  double worstDist() const { return bound_; }
  bool full() const { return heap_.size() == k_; }
  std::size_t size() const { return heap_.size(); }
  bool addPoint(double d2, std::uint32_t index) {
    if (!(d2 <= r2_)) return true;
    const Entry e{d2, index};
    if (heap_.size() < k_) {
      heap_.push_back(e);
      std::push_heap(heap_.begin(), heap_.end());
      if (heap_.size() == k_) bound_ = pruning_bound(heap_.front().first, reach2_);
    } else if (e < heap_.front()) {
      std::pop_heap(heap_.begin(), heap_.end());
      heap_.back() = e;
      std::push_heap(heap_.begin(), heap_.end());
      bound_ = pruning_bound(heap_.front().first, reach2_);
    }
    return true;  // keep searching: nanoflann stops only when told to
  }

 private:
  std::size_t k_;
  double r2_, reach2_, bound_;
  std::vector<Entry>& heap_;
};

// Every photon with distance² <= r2.
class RadiusCollector {
 public:
  RadiusCollector(double r2, double reach2, std::vector<Entry>& found)
      : r2_(r2), bound_(pruning_bound(r2, reach2)), found_(found) {
    found_.clear();
  }
  double worstDist() const { return bound_; }
  bool full() const { return true; }
  std::size_t size() const { return found_.size(); }
  bool addPoint(double d2, std::uint32_t index) {
    if (d2 <= r2_) found_.emplace_back(d2, index);
    return true;
  }

 private:
  double r2_, bound_;
  std::vector<Entry>& found_;
};

// Per-thread scratch for the (distance², index) entries: queries are const and
// run concurrently, so nothing mutable may live in the map; reusing one buffer
// per thread avoids an allocation per query.
std::vector<Entry>& thread_scratch() {
  thread_local std::vector<Entry> scratch;
  return scratch;
}

void check_query(const Vec3& p, double radius_m, const char* what) {
  if (!is_finite(p)) throw Error(std::string("PhotonMap::") + what + ": query point is not finite");
  if (!(radius_m >= 0))
    throw Error(std::string("PhotonMap::") + what + ": radius must be >= 0, got " +
                std::to_string(radius_m));
}

// Copies the sorted entries to `out`, then gives back scratch space beyond
// 1 MiB, so one huge radius query does not leave every thread holding it.
void write_out(std::vector<Entry>& sorted, std::vector<PhotonNeighbour>& out) {
  out.clear();
  out.reserve(sorted.size());
  for (const Entry& e : sorted) out.push_back({e.second, static_cast<float>(e.first)});
  if (sorted.capacity() * sizeof(Entry) > (std::size_t{1} << 20)) std::vector<Entry>().swap(sorted);
}

}  // namespace

struct PhotonMap::Impl {
  std::vector<Photon> photons;
  PhotonSource source;                          // points at `photons`; the tree points at `source`
  std::unique_ptr<Tree> tree;                   // null when there are no photons
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};  // box of the positions
  std::size_t tree_bytes = 0;

  // Squared distance from p to the farthest corner of the box: a bound on
  // every term nanoflann adds into its pruning distance (see pruning_bound).
  double reach2(const Vec3& p) const {
    double s = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = std::max(std::abs(p[a] - lo[a]), std::abs(p[a] - hi[a]));
      s += d * d;
    }
    return s;
  }

  template <class Collector>
  void search(const Vec3& p, Collector& collector) const {
    const double q[3] = {p.x, p.y, p.z};
    // eps = 0: exact search.
    tree->findNeighbors(collector, q, nanoflann::SearchParams(32, 0.0f, false));
  }
};

PhotonMap::PhotonMap(std::vector<Photon> photons, int leaf_size) : impl_(std::make_unique<Impl>()) {
  if (leaf_size < 1)
    throw Error("PhotonMap: leaf_size must be >= 1, got " + std::to_string(leaf_size));
  if (photons.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("PhotonMap: " + std::to_string(photons.size()) +
                " photons exceed the 32-bit index");
  Impl& m = *impl_;
  m.photons = std::move(photons);
  m.source.photons = &m.photons;
  if (m.photons.empty()) return;

  for (int a = 0; a < 3; ++a) m.lo[a] = m.hi[a] = m.photons[0].position_m[a];
  for (std::size_t i = 0; i < m.photons.size(); ++i) {
    const Photon& ph = m.photons[i];
    for (int a = 0; a < 3; ++a) {
      const double x = ph.position_m[a];
      // A NaN would make the tree's splits meaningless: reject it here.
      if (!std::isfinite(x))
        throw Error("PhotonMap: photon " + std::to_string(i) + " has a non-finite position");
      m.lo[a] = std::min(m.lo[a], x);
      m.hi[a] = std::max(m.hi[a], x);
    }
  }
  // nanoflann builds single-threaded in this version (1.4.x): the tree
  // depends only on the photons and leaf_size.
  m.tree = std::make_unique<Tree>(
      3, m.source, nanoflann::KDTreeSingleIndexAdaptorParams(static_cast<std::size_t>(leaf_size)));

  // Store the photons in the tree's leaf order: a leaf's photons are then
  // contiguous, so a query reads a few cache lines per leaf instead of one per
  // photon (about 1.5x more k-NN queries/s at 4e6 photons, docs/photon-map.md), and
  // so does the caller reading the neighbours' powers and directions.
  // new[i] = old[vAcc[i]], applied in place one cycle at a time; it leaves
  // vAcc the identity, which is what the tree must see afterwards.
  std::vector<std::uint32_t>& order = m.tree->vAcc;
  for (std::size_t start = 0; start < order.size(); ++start) {
    if (order[start] == start) continue;  // in place already, or its cycle is done
    const Photon first = m.photons[start];
    std::size_t j = start;
    for (;;) {
      const std::size_t from = order[j];
      order[j] = static_cast<std::uint32_t>(j);
      if (from == start) {
        m.photons[j] = first;
        break;
      }
      m.photons[j] = m.photons[from];
      j = from;
    }
  }

  // Node memory, counted rather than guessed: every node is one allocation of
  // sizeof(Node) rounded up to nanoflann's WORDSIZE from pool blocks of
  // BLOCKSIZE bytes whose first word links the previous block.
  std::size_t nodes = 0;
  std::vector<const Tree::Node*> stack{m.tree->root_node};
  while (!stack.empty()) {
    const Tree::Node* n = stack.back();
    stack.pop_back();
    ++nodes;
    if (n->child1) stack.push_back(n->child1);
    if (n->child2) stack.push_back(n->child2);
  }
  const std::size_t stride =
      (sizeof(Tree::Node) + nanoflann::WORDSIZE - 1) & ~(nanoflann::WORDSIZE - 1);
  const std::size_t per_block = (nanoflann::BLOCKSIZE - sizeof(void*)) / stride;
  m.tree_bytes = (nodes + per_block - 1) / per_block * nanoflann::BLOCKSIZE;
}

PhotonMap::~PhotonMap() = default;
PhotonMap::PhotonMap(PhotonMap&&) noexcept = default;
PhotonMap& PhotonMap::operator=(PhotonMap&&) noexcept = default;

std::size_t PhotonMap::size() const { return impl_ ? impl_->photons.size() : 0; }

const Photon& PhotonMap::operator[](std::size_t i) const { return impl_->photons[i]; }

const std::vector<Photon>& PhotonMap::photons() const {
  static const std::vector<Photon> kNone;  // a moved-from map reads as empty
  return impl_ ? impl_->photons : kNone;
}

void PhotonMap::k_nearest(const Vec3& p, int k, double max_radius_m,
                          std::vector<PhotonNeighbour>& out) const {
  if (k < 0) throw Error("PhotonMap::k_nearest: k must be >= 0, got " + std::to_string(k));
  check_query(p, max_radius_m, "k_nearest");
  out.clear();
  if (k == 0 || size() == 0) return;
  const std::size_t want = std::min(static_cast<std::size_t>(k), size());
  std::vector<Entry>& heap = thread_scratch();
  NearestCollector collector(want, max_radius_m * max_radius_m, impl_->reach2(p), heap);
  impl_->search(p, collector);
  std::sort_heap(heap.begin(), heap.end());
  write_out(heap, out);
}

void PhotonMap::within_radius(const Vec3& p, double radius_m,
                              std::vector<PhotonNeighbour>& out) const {
  check_query(p, radius_m, "within_radius");
  out.clear();
  if (size() == 0) return;
  std::vector<Entry>& found = thread_scratch();
  RadiusCollector collector(radius_m * radius_m, impl_->reach2(p), found);
  impl_->search(p, collector);
  std::sort(found.begin(), found.end());
  write_out(found, out);
}

std::size_t PhotonMap::memory_bytes() const {
  if (!impl_) return 0;
  const Impl& m = *impl_;
  std::size_t bytes = sizeof(Impl) + m.photons.capacity() * sizeof(Photon);
  if (m.tree)
    bytes += sizeof(Tree) + m.tree->vAcc.capacity() * sizeof(std::uint32_t) + m.tree_bytes;
  return bytes;
}

}  // namespace obscura
