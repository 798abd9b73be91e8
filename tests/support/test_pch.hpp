// The precompiled header of every test executable (tests/CMakeLists.txt): GoogleTest, the standard
// library and the host headers most tests include. Parsing them was about half of a test file's compile
// time, in both CI builds. Test files still include what they use; this only makes it cheaper.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <nimbus/nimbus.hpp>

#include "abi/host_services.hpp"
#include "film/film.hpp"
#include "loader/plugin_registry.hpp"
#include "render/render_session.hpp"
#include "scene/scene_parser.hpp"
#include "world/world.hpp"
