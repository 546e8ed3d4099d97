#pragma once
// A box of constant coefficients: the medium of closed-form test cases (slabs,
// furnaces) and a reference for the grid code.
#include <string>
#include <vector>

#include "obscura/medium/medium.h"

namespace obscura {

class HomogeneousMedium final : public Medium {
 public:
  // Coefficients per spectral sample (1/m), g dimensionless, temperature in K.
  // Throws InputError naming `source` on bad values.
  HomogeneousMedium(BBox3 box, std::vector<double> wavelengths_um, std::vector<double> sigma_a,
                    std::vector<double> sigma_s, std::vector<double> g, double temperature_k,
                    const std::string& source = "");

  BBox3 bounds() const override { return box_; }
  const std::vector<double>& wavelengths_um() const override { return wavelengths_um_; }
  void coefficients_at(const Vec3& p, MediumPoint& out) const override;
  void trace_segments(const Ray& ray, double t_min, double t_max,
                      const SegmentVisitor& visit) const override;
  void trace_majorants(const Ray& ray, double t_min, double t_max,
                       const MajorantVisitor& visit) const override;

 private:
  BBox3 box_;
  std::vector<double> wavelengths_um_;
  MediumPoint values_;
  std::vector<Cubic> cubics_;    // σa then σs, constant
  std::vector<double> sigma_t_;  // σa + σs per sample, the exact majorant
};

}  // namespace obscura
