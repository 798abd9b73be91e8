// Preetham, Shirley & Smits 1999, "A Practical Analytic Model for Daylight": sky radiance from the
// sun's position and the atmosphere's turbidity, baked into a lat-long map so that the environment
// light samples it like any HDR image.
#pragma once

#include <vector>

#include <nimbus/cpp/math.hpp>

namespace nimbus {

// Radiance in W/(m^2 sr) per linear Rec.709 channel: Preetham luminance in cd/m^2 divided by 683 lm/W,
// so a sun of ~1000 W/m^2 irradiance balances it as daylight does. Below the horizon: a quarter of the
// horizon's radiance (a dim ground). `to_sun` is unit; `turbidity` in [1.7, 10].
Rgb preetham_sky_radiance(const Vec3f &dir, const Vec3f &to_sun, float turbidity);

// Bakes the sky into a width x height lat-long map (row 0 at +z, u along the azimuth from +x).
std::vector<Rgb> bake_sky(const Vec3f &to_sun, float turbidity, uint32_t width, uint32_t height);

}  // namespace nimbus
