#include "core/ior_curve.hpp"

#include <cmath>
#include <limits>
#include <string>

#include <nimbus/cpp/spectral.hpp>

namespace nimbus {

namespace {

double squared_um(double lambda_nm) { return (lambda_nm * 1e-3) * (lambda_nm * 1e-3); }

bool all_finite(const std::array<double, 3> &v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

const char *model_name(IorCurve::Model m) {
  switch (m) {
    case IorCurve::Model::kConstant:
      return "constant index";
    case IorCurve::Model::kAbbe:
      return "Abbe glass";
    case IorCurve::Model::kCauchy:
      return "Cauchy curve";
    case IorCurve::Model::kSellmeier:
      return "Sellmeier curve";
  }
  return "index curve";
}

}  // namespace

IorCurve IorCurve::constant(double n) {
  IorCurve c;
  c.model_ = Model::kConstant, c.b_ = {n, 0, 0};
  return c;
}

IorCurve IorCurve::abbe(double n_d, double v_d) {
  // n_F - n_C = B (1 / lambda_F^2 - 1 / lambda_C^2) = (n_d - 1) / V_d gives B; n(lambda_d) = n_d gives A.
  const double b = (n_d - 1) / (v_d * (1 / squared_um(kFraunhoferF) - 1 / squared_um(kFraunhoferC)));
  IorCurve c = cauchy(n_d - b / squared_um(kFraunhoferD), b);
  c.model_ = Model::kAbbe, c.c_ = {n_d, v_d, 0};
  return c;
}

IorCurve IorCurve::cauchy(double a, double b_um2, double c_um4) {
  IorCurve c;
  c.model_ = Model::kCauchy, c.b_ = {a, b_um2, c_um4};
  return c;
}

IorCurve IorCurve::sellmeier(const std::array<double, 3> &b, const std::array<double, 3> &c_um2) {
  IorCurve c;
  c.model_ = Model::kSellmeier, c.b_ = b, c.c_ = c_um2;
  return c;
}

double IorCurve::index(double lambda_nm) const {
  const double l2 = squared_um(lambda_nm);
  switch (model_) {
    case Model::kConstant:
      return b_[0];
    case Model::kAbbe:
    case Model::kCauchy:
      return b_[0] + b_[1] / l2 + b_[2] / (l2 * l2);
    case Model::kSellmeier: {
      double n2 = 1;
      for (int i = 0; i < 3; ++i) n2 += b_[i] * l2 / (l2 - c_[i]);
      return n2 >= 0 ? std::sqrt(n2) : std::numeric_limits<double>::quiet_NaN();
    }
  }
  return b_[0];
}

bool IorCurve::dispersive() const {
  switch (model_) {
    case Model::kConstant:
      return false;
    case Model::kAbbe:
    case Model::kCauchy:
      return b_[1] != 0 || b_[2] != 0;
    case Model::kSellmeier:
      for (int i = 0; i < 3; ++i)
        if (b_[i] != 0 && c_[i] != 0) return true;  // C_i = 0 adds the constant B_i to n^2
      return false;
  }
  return false;
}

Status IorCurve::validate() const {
  const std::string name = model_name(model_);
  if (model_ == Model::kAbbe) {
    if (!(c_[0] > 1)) return Error{name + ": n_d " + std::to_string(c_[0]) + " must be above 1"};
    if (!(c_[1] > 0)) return Error{name + ": Abbe number V_d " + std::to_string(c_[1]) + " must be above 0"};
  }
  if (!all_finite(b_) || !all_finite(c_)) return Error{name + ": a coefficient is not finite"};
  // A Sellmeier term whose pole lambda = sqrt(C_i) lies in the range is infinite there, however finely the
  // scan below would step past it.
  if (model_ == Model::kSellmeier)
    for (int i = 0; i < 3; ++i)
      if (b_[i] != 0 && c_[i] >= squared_um(kLambdaMin) && c_[i] <= squared_um(kLambdaMax))
        return Error{name + ": term " + std::to_string(i + 1) + " has a pole at " +
                     std::to_string(std::sqrt(c_[i]) * 1e3) + " nm, inside the visible range"};
  // Every nanometre: between poles these curves change slowly, and an index that fell below 1 for less
  // than a nanometre would take absurd coefficients.
  for (int lambda = int(kLambdaMin); lambda <= int(kLambdaMax); ++lambda) {
    const double n = index(lambda);
    if (!std::isfinite(n) || !(n > 1))
      return Error{name + ": index " + std::to_string(n) + " at " + std::to_string(lambda) +
                   " nm (it must be finite and above 1 from 360 to 830 nm)"};
  }
  return Ok{};
}

double abbe_number(const IorCurve &curve) {
  const double spread = curve.index(kFraunhoferF) - curve.index(kFraunhoferC);
  return spread != 0 ? (curve.index(kFraunhoferD) - 1) / spread : std::numeric_limits<double>::infinity();
}

}  // namespace nimbus
