#pragma once
// A cubic polynomial c0 + c1 s + c2 s² + c3 s³ in the distance s (metres) from
// the start of a ray segment. Trilinear interpolation restricted to a straight
// line inside one cell is exactly such a cubic, so integrals of it along the
// ray are exact (no step size, nothing thin can be skipped).
namespace obscura {

struct Cubic {
  double c[4] = {0, 0, 0, 0};

  double operator()(double s) const { return c[0] + s * (c[1] + s * (c[2] + s * c[3])); }
  // ∫₀ˢ f(u) du, exact.
  double integral(double s) const {
    return s * (c[0] + s * (c[1] / 2.0 + s * (c[2] / 3.0 + s * c[3] / 4.0)));
  }
  bool is_constant() const { return c[1] == 0.0 && c[2] == 0.0 && c[3] == 0.0; }
  bool is_zero() const { return c[0] == 0.0 && is_constant(); }

  Cubic& operator+=(const Cubic& o) {
    for (int i = 0; i < 4; ++i) c[i] += o.c[i];
    return *this;
  }
  Cubic operator*(double k) const { return {{c[0] * k, c[1] * k, c[2] * k, c[3] * k}}; }
  Cubic operator+(const Cubic& o) const {
    Cubic r = *this;
    r += o;
    return r;
  }
  static Cubic constant(double v) { return {{v, 0, 0, 0}}; }
  // The same polynomial in a variable shifted by d: q(s) = p(s + d).
  Cubic shifted(double d) const {
    return {{c[0] + d * (c[1] + d * (c[2] + d * c[3])), c[1] + d * (2.0 * c[2] + 3.0 * d * c[3]),
             c[2] + 3.0 * d * c[3], c[3]}};
  }
};

}  // namespace obscura
