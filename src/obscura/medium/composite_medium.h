#pragma once
// Several media seen as one (overlapping clouds): extinction and scattering
// coefficients add, g is weighted by σs, and each medium emits at its own
// temperature. Along a ray the children's segments are merged at the union of
// their breakpoints; every merged segment lists one component per child present.
#include <memory>
#include <string>
#include <vector>

#include "obscura/medium/medium.h"

namespace obscura {

class CompositeMedium final : public Medium {
 public:
  // The children must share the same spectral samples; throws InputError
  // naming `source` otherwise. Null children are ignored.
  CompositeMedium(std::vector<std::shared_ptr<const Medium>> children,
                  const std::string& source = "");

  BBox3 bounds() const override { return bounds_; }
  const std::vector<double>& wavelengths_um() const override { return wavelengths_um_; }
  // Sums of σa and σs, σs-weighted g, and the σa-weighted mean temperature (a
  // summary: emission from overlapping media at different temperatures is
  // exact only through trace_segments, which keeps them apart).
  void coefficients_at(const Vec3& p, MediumPoint& out) const override;
  void trace_segments(const Ray& ray, double t_min, double t_max,
                      const SegmentVisitor& visit) const override;
  // The sum of the children's bounds over the union of their pieces.
  void trace_majorants(const Ray& ray, double t_min, double t_max,
                       const MajorantVisitor& visit) const override;
  // One cloud: its grid; several: an axis-aligned grid over all of them at
  // the finest voxel size among them.
  std::optional<GridFrame> grid_frame() const override;
  bool may_be_nonzero(const BBox3& world_box) const override;
  // One cloud: its own march; several: the default (from the merged segments).
  void march_cells(const Ray& ray, double t_min, double t_max, const MarchOptions& options,
                   MarchVisitor& visit) const override;

  std::size_t size() const { return children_.size(); }

 private:
  std::vector<std::shared_ptr<const Medium>> children_;
  std::vector<double> wavelengths_um_;
  BBox3 bounds_;
};

}  // namespace obscura
