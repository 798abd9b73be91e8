#include "furnace.hpp"

namespace nimbus::test {

double albedo_floor(float alpha, float theta_deg) {
  static constexpr float kFloorAngles[] = {0, 30, 60, 80, 89};
  static constexpr struct {
    float alpha;
    double floor[5];
  } kTable[] = {{0.05f, {0.94, 0.94, 0.94, 0.90, 0.57}}, {0.2f, {0.89, 0.87, 0.81, 0.74, 0.48}},
                {0.3f, {0.82, 0.79, 0.72, 0.67, 0.47}},  {0.5f, {0.63, 0.61, 0.60, 0.56, 0.46}},
                {0.8f, {0.37, 0.39, 0.48, 0.44, 0.45}},  {1.0f, {0.25, 0.28, 0.39, 0.40, 0.40}}};
  const float from_normal = std::min(theta_deg, 180 - theta_deg);
  for (const auto &row : kTable)
    if (row.alpha == alpha)
      for (int i = 0; i < 5; ++i)
        if (kFloorAngles[i] == from_normal) return row.floor[i];
  ADD_FAILURE() << "no albedo floor for alpha " << alpha << " theta " << theta_deg;
  return 1;
}

}  // namespace nimbus::test
