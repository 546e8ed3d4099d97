#pragma once
// Where a radiance cache's light is needed: the lattice cells that pinhole
// sensors' camera rays can read, with a margin. A narrow sensor (the demo's
// 1.2° television camera) sees a thin wedge of a wide cloud, and the
// track-length splat (flight_splat.h) then walks only the flights' parts in
// the box around that wedge. The light of a node inside the box's core comes
// out with the same bits as without the box: the walker's cell crossings do
// not depend on where a walk starts, and a node's estimate reads only the
// cells within `margin_nodes` of it (docs/physics.md, "Only where the sensors
// look").
#include <algorithm>
#include <array>
#include <limits>
#include <vector>

#include "obscura/render/lattice/node_lattice.h"
#include "obscura/scene/camera.h"

namespace obscura {

// Cells lo[a] … hi[a] (inclusive) along each lattice axis; a cell (i, j, k)
// spans lattice coordinates [i, i + 1] × [j, j + 1] × [k, k + 1].
// Default: empty.
struct CellBox {
  static constexpr int kNone = std::numeric_limits<int>::max();
  std::array<int, 3> lo{kNone, kNone, kNone}, hi{-1, -1, -1};
  bool empty() const { return hi[0] < lo[0] || hi[1] < lo[1] || hi[2] < lo[2]; }
  long long count() const {
    return empty() ? 0
                   : static_cast<long long>(hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) *
                         (hi[2] - lo[2] + 1);
  }
  // Grows to the bounds of this box and `other` (an empty one adds nothing).
  void add(const CellBox& other) {
    if (other.empty()) return;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], other.lo[a]);
      hi[a] = std::max(hi[a], other.hi[a]);
    }
  }
};

// Every cell of the lattice.
CellBox all_cells(const NodeLattice& lattice);

// The box around the cells of `lattice`'s held blocks that some camera's
// view pyramid (its four corner rays from its position) may reach, tested
// by blocks and then by parts of 2³ cells (each grown by half a spacing),
// grown by `margin_nodes` cells and clipped to the lattice; all_cells for a
// periodic lattice (whose rays wrap around). Empty when no camera sees any
// block.
CellBox cells_in_view(const NodeLattice& lattice, const std::vector<const PinholeCamera*>& cameras,
                      int margin_nodes);

}  // namespace obscura
