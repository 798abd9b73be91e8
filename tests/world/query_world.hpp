// A world built from a scene's text, with the host services a plugin would see: what the scene-query
// tests of this directory (sharp_bounds, moving_bounds) ask their questions of.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "abi/host_services.hpp"
#include "scene/scene_parser.hpp"
#include "world/world.hpp"

namespace nimbus {

struct QueryWorld {
  SceneDesc desc;
  std::unique_ptr<World> world;
  std::unique_ptr<HostServices> services;
  const nimbus_host_scene_query_v1_t *query = nullptr;

  // Fails the test (and leaves query null) when the scene does not parse or build.
  explicit QueryWorld(const std::string &text) {
    auto d = parse_scene_string(text, "query.yaml");
    EXPECT_TRUE(d.ok()) << d.error().message;
    if (!d.ok()) return;
    desc = std::move(d.value());
    auto w = World::build(desc, desc.render.filter);
    EXPECT_TRUE(w.ok()) << w.error().message;
    if (!w.ok()) return;
    world = std::move(w.value());
    services = std::make_unique<HostServices>(world.get());
    query = static_cast<const nimbus_host_scene_query_v1_t *>(
        services->host()->get_service(services->host(), NIMBUS_SERVICE_SCENE_QUERY, 1));
  }
  const nimbus_host_t *host() const { return services->host(); }
};

}  // namespace nimbus
