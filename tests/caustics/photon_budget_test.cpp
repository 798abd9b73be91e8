// The photon memory budget (photon_budget.hpp): a pass whose photons could need more memory than the
// budget traces fewer paths instead of failing, every pass within the budget, and the render still
// converges to the same image, only with fewer photons.
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>

#include "photon_budget.hpp"
#include "sphere_scenes.hpp"
#include "support/render_support.hpp"

namespace nimbus::testing {
namespace photon_budget_test {

using caustics::kPhotonsPerPathCap;
using caustics::Photon;
using caustics::PhotonBudget;

TEST(CausticsPhotonBudget, WorstCaseOfTheAllowedPathsFitsTheBudget) {
  for (uint64_t mb : {1, 64, 4096}) {
    const PhotonBudget budget(mb);
    EXPECT_EQ(budget.bytes(), mb << 20);
    for (double map_bytes : {0.0, 70.0, 400.0}) {
      const uint64_t fit = budget.paths_within(std::numeric_limits<uint64_t>::max(), map_bytes);
      EXPECT_LE(budget.worst_bytes(fit, map_bytes), double(budget.bytes()));
      EXPECT_GT(budget.worst_bytes(fit + 1, map_bytes), double(budget.bytes()));
      EXPECT_EQ(budget.paths_within(fit / 2, map_bytes), fit / 2) << "a pass within the budget is untouched";
    }
  }
  EXPECT_GT(PhotonBudget(0).bytes(), uint64_t(0)) << "0: a quarter of the machine's memory";
}

TEST(CausticsPhotonBudget, PassesShrinkToTheBudgetAndTheImageStillAgrees) {
  SceneRenderer r;
  const std::string scene = from_above(R"(
lights:
  - { type: point, position: [-2.0, 0, 1.6], intensity: [12, 12, 12], group: key }
)",
                                       2);
  RenderRequest q = request("nimbus.caustics", 64, 5);
  const auto free_run = r.render(scene, q);
  q.options = {{"photon_memory_mb", "1"}};
  const auto budgeted = r.render(scene, q);
  // Every pass of the budgeted render fits 1 MiB at the per-path guard's worst case, whatever the map's
  // index costs (at least 1.5 photons' size per photon).
  const double max_paths = double(1 << 20) / (double(kPhotonsPerPathCap) * 2.5 * sizeof(Photon));
  const double free_paths =
      stat(free_run, "caustics_photon_paths") / stat(free_run, "caustics_photon_passes");
  const double paths = stat(budgeted, "caustics_photon_paths") / stat(budgeted, "caustics_photon_passes");
  const double stored = stat(budgeted, "caustics_photons") / stat(budgeted, "caustics_photon_passes") *
                        stat(budgeted, "caustics_bytes_per_photon");
  std::printf(
      "photon paths per pass: %.0f without a budget, %.0f within 1 MiB (at most %.0f); %.0f KiB stored\n",
      free_paths, paths, max_paths, stored / 1024);
  EXPECT_GT(free_paths, 4 * max_paths)
      << "the scene must need more than the budget, or the test shows nothing";
  EXPECT_LE(paths, max_paths);
  EXPECT_GT(paths, 0.0);
  EXPECT_LE(stored, double(1 << 20));
  // Fewer photons, same estimate: the caustic region's means agree within their noise (the budgeted
  // render's photon noise dominates: 8 % is several of its standard errors at this count).
  const Region caustic{80, 28, 120, 64};
  const double a = region_mean(free_run, caustic), b = region_mean(budgeted, caustic);
  std::printf("caustic region mean: %.4f without a budget, %.4f within 1 MiB\n", a, b);
  EXPECT_NEAR(b / a, 1.0, 0.08);
}

}  // namespace photon_budget_test
}  // namespace nimbus::testing
