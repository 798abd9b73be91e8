#include "furnace.hpp"

#include "support/ggx_reference.hpp"

namespace nimbus::test {

namespace {

template <class Weight>
double integrate(double eta, double alpha, const Vec3f &wo, int n, Weight weight) {
  const reference::V3 w = reference::unit({wo.x, wo.y, wo.z});
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const reference::Bounce b = reference::bounce(w, eta, alpha, (i + 0.5) / n, (j + 0.5) / n);
      sum += weight(b);
    }
  return sum / (double(n) * n);
}

}  // namespace

double ggx_albedo_lower_bound(double eta, double alpha, const Vec3f &wo, int n) {
  return integrate(eta, alpha, wo, n, [](const reference::Bounce &b) {
    return b.fresnel * b.w_reflect + (1 - b.fresnel) * b.w_refract;
  });
}

double ggx_albedo_height_correlated(double eta, double alpha, const Vec3f &wo, int n) {
  return integrate(eta, alpha, wo, n, [](const reference::Bounce &b) {
    return b.fresnel * b.w_reflect_correlated + (1 - b.fresnel) * b.w_refract_correlated;
  });
}

}  // namespace nimbus::test
