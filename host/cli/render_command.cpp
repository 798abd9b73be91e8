// `nimbus render SCENE`: parse, render progressively, write EXR + PNG. Ctrl-C finishes the current
// iteration and writes complete files; a second Ctrl-C ends the process at once.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>

#include "abi/host_services.hpp"
#include "cli/commands.hpp"
#include "cli/progress_display.hpp"
#include "core/install_layout.hpp"
#include "loader/plugin_registry.hpp"
#include "render/render_session.hpp"
#include "scene/pixel_filter_type.hpp"
#include "scene/scene_parser.hpp"

namespace nimbus::cli {
namespace {

constexpr const char *kHelp =
    "usage: nimbus render SCENE.yaml [options]\n"
    "\n"
    "Renders SCENE progressively and writes a multi-layer EXR and a PNG preview beside it. SCENE may name\n"
    "an installed scene (share/nimbus/scenes), e.g. default.yaml or caustics/pool.yaml.\n"
    "\n"
    "options:\n"
    "  -o, --output OUT.exr   output image (default: out/<scene name>.exr); the PNG gets the same stem\n"
    "  --iterations N         samples per pixel\n"
    "  --time SECONDS         time budget\n"
    "  --target-error X       stop when the estimated relMSE of the image falls below X (no reference\n"
    "                         needed: estimated from odd and even iterations)\n"
    "                         Any of these three replaces all of the scene's stopping rules; given\n"
    "                         together, the first one reached stops the render.\n"
    "  --threads N            worker threads (default: all cores)\n"
    "  --seed S               random seed (overrides the scene)\n"
    "  --elements a,b,...     render elements besides beauty (added to the scene's)\n"
    "  --integrator ID        integrator plugin (overrides the scene; default caustics), e.g. pt, nimbus.pt\n"
    "  --light-sampler ID     light sampler plugin (default: nimbus.lights.tree above 8 lights,\n"
    "                         nimbus.lights.power otherwise)\n"
    "  --guide ID|none        guiding plugin (default: the integrator's own, e.g. nimbus.guide.metropolis\n"
    "                         for the caustics solver)\n"
    "  --filter NAME          pixel filter: box, gaussian, blackman-harris (overrides the scene)\n"
    "  --region x0,y0,x1,y1   render only this pixel rectangle (crop window); the rest stays black\n"
    "  --NAME VALUE           an option the integrator declares (`nimbus plugins --options ID` lists\n"
    "                         them), e.g. --caustics off; the same as the scene's render.NAME\n"
    "  -q, --quiet            no progress output\n"
    "  --checkpoint PATH      checkpoint file (default: OUT.exr.ckpt)\n"
    "  --checkpoint-every S   seconds between checkpoints (default 300; 0: only when the render stops)\n"
    "  --resume               continue from the checkpoint; --iterations is then the total, old + new\n"
    "  --task K --tasks N     render task K (0 to N-1) of N that share the frame: its iterations K+1,\n"
    "                         K+1+N, ... of the frame's --iterations, as a partial EXR (default\n"
    "                         out/<scene name>.part<K>of<N>.exr, no PNG) for `nimbus merge`; --time and\n"
    "                         --target-error apply to each task on its own\n"
    "\n"
    "Ctrl-C (or SIGTERM) stops after the current iteration and writes the image so far (exit code 130;\n"
    "143 for SIGTERM); a second one stops at once.\n"
    "\n"
    "Checkpoints hold the exact sums of every element: the render writes one every --checkpoint-every\n"
    "seconds and whenever it stops (finished, time budget, Ctrl-C), and keeps it, so an interrupted or\n"
    "finished render continues with --resume (same scene, seed, integrator and elements) and ends bit for\n"
    "bit where an uninterrupted render of the same total iterations would.\n";

std::atomic<bool> g_cancel{false};
std::atomic<int> g_stop_signal{0};  // the signal that asked the render to stop (SIGINT or SIGTERM)

// Ctrl-C, or a SIGTERM from a scheduler or `kill`: finish the iteration and write the files.
extern "C" void on_stop_signal(int sig) {
  int none = 0;
  g_stop_signal.compare_exchange_strong(none, sig);
  if (g_cancel.exchange(true)) {
    // The second one: the user (or the scheduler) insists. Restore the default action and re-raise.
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

struct Args {
  std::string scene;
  RenderOptions options;
  std::vector<RenderDesc::OptionSetting> integrator_options;  // --NAME VALUE flags the CLI does not know
  std::optional<std::array<uint32_t, 4>> region;
  bool quiet = false;
  std::optional<uint32_t> task, tasks;
};

constexpr uint32_t kMaxTasks = 100000;

template <class T>
bool parse_number(const std::string &s, T &out) {
  const char *end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end;
}

// `--name` or `--name=value` with a name an integrator could declare ([a-z][a-z0-9_]*).
bool is_option_flag(const std::string &k) {
  if (k.size() < 3 || k.compare(0, 2, "--") != 0 || !std::islower(static_cast<unsigned char>(k[2])))
    return false;
  for (size_t i = 3; i < k.size() && k[i] != '='; ++i)
    if (!std::islower(static_cast<unsigned char>(k[i])) && !std::isdigit(static_cast<unsigned char>(k[i])) &&
        k[i] != '_')
      return false;
  return true;
}

// Returns an error message, or an empty string on success.
std::string parse_args(const std::vector<std::string> &args, Args &a, bool &help) {
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &k = args[i];
    auto value = [&](std::string &out) -> bool {
      if (i + 1 >= args.size()) return false;
      out = args[++i];
      return true;
    };
    std::string v;
    if (k == "--help" || k == "-h") {
      help = true;
      return "";
    } else if (k == "-q" || k == "--quiet") {
      a.quiet = true;
    } else if (k == "-o" || k == "--output") {
      if (!value(v) || v.empty()) return k + ": expected a file name";
      a.options.output_exr = v;
    } else if (k == "--iterations") {
      uint64_t n = 0;
      if (!value(v) || !parse_number(v, n) || n == 0)
        return "--iterations: expected a positive integer, got '" + v + "'";
      a.options.iterations = n;
    } else if (k == "--time") {
      double t = 0;
      if (!value(v) || !parse_number(v, t) || !(t > 0))
        return "--time: expected a positive number of seconds, got '" + v + "'";
      a.options.time_seconds = t;
    } else if (k == "--target-error") {
      double t = 0;
      if (!value(v) || !parse_number(v, t) || !(t > 0))
        return "--target-error: expected a positive number, got '" + v + "'";
      a.options.target_error = t;
    } else if (k == "--threads") {
      uint32_t n = 0;
      if (!value(v) || !parse_number(v, n) || n == 0 || n > 4096)
        return "--threads: expected an integer in [1, 4096], got '" + v + "'";
      a.options.threads = n;
    } else if (k == "--seed") {
      uint64_t s = 0;
      if (!value(v) || !parse_number(v, s)) return "--seed: expected a non-negative integer, got '" + v + "'";
      a.options.seed = s;
    } else if (k == "--elements") {
      if (!value(v) || v.empty()) return "--elements: expected a comma-separated list";
      std::stringstream ss(v);
      for (std::string e; std::getline(ss, e, ',');)
        if (!e.empty()) a.options.elements.push_back(e);
    } else if (k == "--filter") {
      a.options.filter = value(v) ? filter_from_name(v) : std::nullopt;
      if (!a.options.filter) return "--filter: expected one of " + filter_names() + ", got '" + v + "'";
    } else if (k == "--region") {
      std::array<uint32_t, 4> r{};
      std::stringstream ss(value(v) ? v : std::string());
      std::string part;
      int n = 0;
      bool ok = true;
      while (std::getline(ss, part, ',')) ok = ok && n < 4 && parse_number(part, r[n++]);
      if (!ok || n != 4 || r[2] <= r[0] || r[3] <= r[1])
        return "--region: expected x0,y0,x1,y1 with x1 > x0 and y1 > y0, got '" + v + "'";
      a.region = r;
    } else if (k == "--light-sampler") {
      if (!value(v) || v.empty()) return "--light-sampler: expected a plugin id";
      a.options.light_sampler = v;
    } else if (k == "--guide") {
      if (!value(v) || v.empty()) return "--guide: expected a plugin id or 'none'";
      a.options.guide = v;
    } else if (k == "--integrator") {
      if (!value(v) || v.empty()) return "--integrator: expected a plugin id";
      a.options.integrator = v;
    } else if (k == "--checkpoint") {
      if (!value(v) || v.empty()) return "--checkpoint: expected a file name";
      a.options.checkpoint_path = v;
    } else if (k == "--checkpoint-every") {
      double t = 0;
      if (!value(v) || !parse_number(v, t) || !(t >= 0) || !std::isfinite(t))
        return "--checkpoint-every: expected a non-negative number of seconds, got '" + v + "'";
      a.options.checkpoint_interval_seconds = t;
    } else if (k == "--resume") {
      a.options.resume = true;
    } else if (k == "--task" || k == "--tasks") {
      uint32_t n = 0;
      if (!value(v) || !parse_number(v, n) || (k == "--tasks" && (n == 0 || n > kMaxTasks)))
        return k + ": expected " +
               (k == "--task" ? "a task number from 0" : "a task count from 1 to 100000") + ", got '" + v +
               "'";
      (k == "--task" ? a.task : a.tasks) = n;
    } else if (is_option_flag(k)) {
      // Not a flag of the render command: an option of the integrator, checked once it is bound.
      const size_t eq = k.find('=');
      std::string name = k.substr(2, eq == std::string::npos ? std::string::npos : eq - 2);
      // The value is the next argument unless that is another flag (a negative number is a value).
      const auto is_value = [](const std::string &s) {
        return !s.empty() &&
               (s[0] != '-' ||
                (s.size() > 1 && (std::isdigit(static_cast<unsigned char>(s[1])) || s[1] == '.')));
      };
      if (eq != std::string::npos)
        v = k.substr(eq + 1);
      else if (i + 1 < args.size() && is_value(args[i + 1]))
        v = args[++i];
      else
        return k + ": expected a value (an integrator option: --NAME VALUE)";
      a.integrator_options.push_back(
          {name, v, "--" + name, "see `nimbus render --help` for the render command's flags"});
    } else if (!k.empty() && k[0] == '-') {
      return "unknown option '" + k + "'";
    } else if (a.scene.empty()) {
      a.scene = k;
    } else {
      return "unexpected argument '" + k + "' (one scene per render)";
    }
  }
  if (a.scene.empty()) return "no scene given";
  if (a.task.has_value() != a.tasks.has_value()) return "--task and --tasks go together";
  if (a.tasks && *a.task >= *a.tasks)
    return "--task " + std::to_string(*a.task) + " is not one of the tasks 0 to " +
           std::to_string(*a.tasks - 1);
  a.options.task = a.task.value_or(0), a.options.tasks = a.tasks.value_or(1);
  return "";
}

}  // namespace

int render_command(const std::vector<std::string> &argv) {
  Args a;
  bool help = false;
  if (const std::string err = parse_args(argv, a, help); !err.empty()) {
    std::fprintf(stderr, "nimbus render: %s\n\n%s", err.c_str(), kHelp);
    return kExitUsage;
  }
  if (help) {
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  const auto loading = std::chrono::steady_clock::now();  // the time to first pixel starts here
  // A relative path that names no file may name an installed scene: `nimbus render default.yaml`.
  if (std::error_code ec;
      !std::filesystem::exists(a.scene, ec) && std::filesystem::path(a.scene).is_relative())
    if (const auto installed = installed_data_dir() / "scenes" / a.scene;
        std::filesystem::exists(installed, ec))
      a.scene = installed.string();
  auto scene = parse_scene_file(a.scene);
  if (!scene) {
    std::fprintf(stderr, "%s\n", scene.error().message.c_str());
    return kExitFailure;
  }
  SceneDesc &desc = scene.value();
  for (const std::string &warning : desc.warnings) std::fprintf(stderr, "%s\n", warning.c_str());
  for (auto &o : a.integrator_options) desc.render.options.push_back(std::move(o));
  if (a.region) {
    if ((*a.region)[2] > desc.render.width || (*a.region)[3] > desc.render.height) {
      std::fprintf(stderr, "nimbus render: --region exceeds the image (%ux%u)\n", desc.render.width,
                   desc.render.height);
      return kExitUsage;
    }
    std::copy(a.region->begin(), a.region->end(), desc.render.region);
  }
  if (a.options.output_exr.empty()) {
    const std::string part = a.options.tasks > 1 ? ".part" + std::to_string(a.options.task) + "of" +
                                                       std::to_string(a.options.tasks)
                                                 : "";
    a.options.output_exr =
        (std::filesystem::path("out") / std::filesystem::path(a.scene).stem()).string() + part + ".exr";
  }
  {
    // Create the output directory so a render never fails at the very end for want of it.
    std::error_code ec;
    const auto parent = std::filesystem::path(a.options.output_exr).parent_path();
    if (!parent.empty()) std::filesystem::create_directories(parent, ec);
    if (ec) {
      std::fprintf(stderr, "nimbus render: cannot create directory %s: %s\n", parent.c_str(),
                   ec.message().c_str());
      return kExitFailure;
    }
    // A directory the render cannot write into (read-only, no permission) is found now, not after the
    // render: a file is made where the image's temporary will be, and removed.
    const std::string probe = a.options.output_exr + ".tmp-" + std::to_string(::getpid());
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
    if (fd < 0) {
      std::fprintf(stderr, "nimbus render: cannot write into %s: %s\n",
                   parent.empty() ? "the current directory" : parent.c_str(), std::strerror(errno));
      return kExitFailure;
    }
    ::close(fd);
    ::unlink(probe.c_str());
  }

  HostServices discovery_host(nullptr);
  PluginRegistry registry;
  registry.discover(PluginRegistry::default_search_paths(executable_path()), discovery_host.host());

  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);

  ProgressDisplay display(stderr, isatty(STDERR_FILENO) != 0, a.quiet);
  a.options.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - loading).count();
  auto result = render(
      desc, a.options, registry, g_cancel, [&](const RenderProgress &p) { display.update(p); },
      [&](int level, const std::string &line) {
        if (level < NIMBUS_LOG_WARNING) return;
        display.finish();
        std::fprintf(stderr, "nimbus: %s: %s\n", level >= NIMBUS_LOG_ERROR ? "error" : "warning",
                     line.c_str());
      });
  display.finish();
  if (!result) {
    std::fprintf(stderr, "nimbus: error: %s\n", result.error().message.c_str());
    return kExitFailure;
  }
  const RenderResult &r = result.value();
  if (!a.quiet && r.png_path.empty())
    std::fprintf(stderr,
                 "nimbus: %llu iterations in %.2f s -> %s (task %u of %u; join with nimbus merge)%s\n",
                 (unsigned long long)r.iterations, r.seconds, r.exr_path.c_str(), a.options.task,
                 a.options.tasks, r.cancelled ? " (interrupted)" : "");
  else if (!a.quiet)
    std::fprintf(stderr, "nimbus: %llu iterations in %.2f s -> %s, %s%s\n", (unsigned long long)r.iterations,
                 r.seconds, r.exr_path.c_str(), r.png_path.c_str(), r.cancelled ? " (interrupted)" : "");
  if (!a.quiet && r.resumed_from)
    std::fprintf(stderr, "nimbus: resumed from iteration %llu\n", (unsigned long long)r.resumed_from);
  if (!a.quiet && !r.checkpoint_path.empty())
    std::fprintf(stderr, "nimbus: checkpoint %s (continue with --resume)\n", r.checkpoint_path.c_str());
  // The shell's convention, 128 + the signal: 130 for Ctrl-C, 143 for SIGTERM.
  if (r.cancelled && g_stop_signal.load() == SIGTERM) return 128 + SIGTERM;
  return r.cancelled ? kExitInterrupted : kExitOk;
}

std::string executable_path() {
  std::error_code ec;
  const auto p = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::string() : p.string();
}

}  // namespace nimbus::cli
