// nimbus: the command-line renderer.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <nimbus/version.h>

#include "cli/commands.hpp"

namespace {

constexpr const char *kUsage =
    "usage: nimbus <command> [options]\n"
    "\n"
    "commands:\n"
    "  render SCENE.yaml   render a scene to a multi-layer EXR and a PNG preview\n"
    "  plugins             list the plugins found, with their status\n"
    "  lightmix IN.exr     relight a LightMix render: --set GROUP=SCALE[,R,G,B] ... -o OUT.exr\n"
    "  compare TEST REF    error metrics (RMSE, relMSE, MAPE) of an EXR against a reference\n"
    "  merge PART.exr...   join the parts of a frame rendered with --task K --tasks N: -o OUT.exr\n"
    "\n"
    "  nimbus --version    print the version\n"
    "  nimbus <command> --help   help on a command\n";

}  // namespace

int main(int argc, char **argv) {
  using namespace nimbus::cli;
  if (argc < 2) {
    std::fputs(kUsage, stderr);
    return kExitUsage;
  }
  const std::string cmd = argv[1];
  const std::vector<std::string> args(argv + 2, argv + argc);
  if (cmd == "--version" || cmd == "version") {
    // The ABI this host serves comes from the SDK headers it was built with, never a literal.
    std::printf("nimbus %s (SDK ABI %d.%d.%d)\n", NIMBUS_VERSION_STRING, NIMBUS_ABI_MAJOR, NIMBUS_ABI_MINOR,
                NIMBUS_ABI_PATCH);
    return kExitOk;
  }
  if (cmd == "--help" || cmd == "-h" || cmd == "help") {
    std::fputs(kUsage, stdout);
    return kExitOk;
  }
  if (cmd == "render") return render_command(args);
  if (cmd == "plugins") return plugins_command(args);
  if (cmd == "lightmix") return lightmix_command(args);
  if (cmd == "compare") return compare_command(args);
  if (cmd == "merge") return merge_command(args);
  std::fprintf(stderr, "nimbus: unknown command '%s'\n\n%s", cmd.c_str(), kUsage);
  return kExitUsage;
}
