#include "furnace.hpp"

#include "support/ggx_reference.hpp"

namespace nimbus::test {

double ggx_albedo_lower_bound(double eta, double alpha, const Vec3f &wo, int n) {
  const reference::V3 w = reference::unit({wo.x, wo.y, wo.z});
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const reference::Bounce b = reference::bounce(w, eta, alpha, (i + 0.5) / n, (j + 0.5) / n);
      sum += b.fresnel * b.w_reflect + (1 - b.fresnel) * b.w_refract;
    }
  return sum / (double(n) * n);
}

}  // namespace nimbus::test
