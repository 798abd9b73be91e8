// Index of refraction as a function of wavelength, for dispersive dielectrics: a constant, a glass given by
// its catalogue pair (n_d, Abbe number V_d), or Cauchy's and Sellmeier's equations with published
// coefficients. Wavelengths are in nm at the interface; the equations' coefficients are in micrometres, as
// catalogues print them.
#pragma once

#include <array>

#include "core/expected.hpp"

namespace nimbus {

// The Fraunhofer lines that define n_d and V_d = (n_d - 1) / (n_F - n_C) (nm): helium d, hydrogen F and C.
inline constexpr double kFraunhoferD = 587.56;
inline constexpr double kFraunhoferF = 486.13;
inline constexpr double kFraunhoferC = 656.27;

class IorCurve {
 public:
  enum class Model { kConstant, kAbbe, kCauchy, kSellmeier };

  IorCurve() = default;  // the constant 1.5
  static IorCurve constant(double n);
  // The two-term Cauchy curve n = A + B / lambda^2 through n_d whose Abbe number is v_d: the usual way a
  // scene names a glass. A larger V_d disperses less.
  static IorCurve abbe(double n_d, double v_d);
  // n = A + B / lambda^2 + C / lambda^4, lambda in um (B in um^2, C in um^4).
  static IorCurve cauchy(double a, double b_um2, double c_um4 = 0);
  // n^2 = 1 + sum_i B_i lambda^2 / (lambda^2 - C_i), lambda in um (C_i in um^2), as in Schott's catalogue.
  static IorCurve sellmeier(const std::array<double, 3> &b, const std::array<double, 3> &c_um2);

  Model model() const { return model_; }
  // The index at lambda_nm, in double (what the Abbe number of a curve needs: n_F - n_C is ~1e-2).
  double index(double lambda_nm) const;
  float at(float lambda_nm) const { return float(index(lambda_nm)); }
  // Whether the index changes with wavelength, i.e. whether a path through it must turn monochromatic.
  bool dispersive() const;
  // A message for the scene loader when the curve is unusable: a coefficient not finite, V_d <= 0, or an
  // index that is not finite or not above 1 somewhere in the visible range (360-830 nm).
  Status validate() const;

 private:
  Model model_ = Model::kConstant;
  std::array<double, 3> b_ = {1.5, 0, 0};  // constant: n; Cauchy and Abbe: A, B, C; Sellmeier: B_i
  std::array<double, 3> c_ = {0, 0, 0};    // Sellmeier: C_i; Abbe: the n_d and V_d it was given
};

// (n_d - 1) / (n_F - n_C) of a curve; infinite when it does not disperse.
double abbe_number(const IorCurve &curve);

}  // namespace nimbus
