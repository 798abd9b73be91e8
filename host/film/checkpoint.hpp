// Checkpoints: the film's running double sums saved bit for bit, so an interrupted (or finished) render
// can be continued and end exactly where an uninterrupted render of the same total would.
//
// File format, version 2 (version 1, without plugin states, is still read). Every integer is little-endian;
// doubles are IEEE-754 binary64, little-endian.
//   magic        8 bytes   "NIMBUSCK"
//   version      u32       kCheckpointVersion
//   width        u32
//   height       u32
//   iterations   u64       completed iterations the sums hold
//   seed         u64
//   nonfinite    u64       samples dropped so far for being NaN or infinite
//   seconds      f64       render time the sums took, over all sessions
//   integrator   string    u32 byte count, then the bytes (no terminator)
//   fingerprint  string
//   elements     u32       count, then per active element (film order, beauty first):
//                            name string, channels u32, width * height * channels f64 sums
//   states       u32       count, then per plugin that saved its learnt state (nimbus/render_state.h):
//                            plugin id string, u64 byte count, the plugin's bytes
//   checksum     u64       of every byte before it (core/checksum.hpp), so corruption is detected
//                          rather than resumed from
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "core/expected.hpp"
#include "film/film.hpp"

namespace nimbus {

inline constexpr uint32_t kCheckpointVersion = 2;

// What one plugin saved of its learnt state (nimbus.iface.render-state), in its own format.
struct PluginState {
  std::string plugin;  // id
  std::vector<uint8_t> bytes;
};

struct CheckpointInfo {
  // Completed iterations. Written from the film (this field is ignored by write_checkpoint); filled in by
  // read_checkpoint.
  uint64_t iterations = 0;
  uint64_t seed = 0;
  // What the sums depend on, as "key=value" lines (RenderJob::fingerprint); read_checkpoint compares
  // them line by line, so a mismatch names what changed.
  std::string fingerprint;
  std::string integrator;  // plugin id
  double seconds = 0;      // render time the sums took, over all sessions
  // Written as given; filled in by read_checkpoint (empty from a version 1 file).
  std::vector<PluginState> states;
};

// Writes every active element's sums atomically (temporary file, fsync, rename: see atomic_file.hpp), so a
// crash mid-write leaves the previous checkpoint intact. The film must have no pending splats.
Status write_checkpoint(const Film &film, const std::string &path, const CheckpointInfo &info);

// Restores `film` from the checkpoint at `path`: the sums of every active element, the iteration count
// and the non-finite sample count. On input `info.seed`, `info.fingerprint` and `info.integrator` describe
// the render about to continue and must match the file, as must the film's size and active elements
// (names and channel counts); on success `info.iterations` and `info.seconds` are the file's. Everything
// is validated before the film is touched: on any error (missing, truncated or corrupted file, wrong
// magic or version, a mismatch) the film is unchanged and the message names the path and the reason.
Status read_checkpoint(Film &film, const std::string &path, CheckpointInfo &info);

// The header alone (iterations, seed, fingerprint, integrator, seconds), without validating the data: to
// report what a checkpoint holds before deciding to resume or replace it.
Expected<CheckpointInfo> peek_checkpoint(const std::string &path);

}  // namespace nimbus
