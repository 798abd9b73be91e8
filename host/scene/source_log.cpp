#include "scene/source_log.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "core/checksum.hpp"

namespace nimbus {
namespace {

std::filesystem::path absolute_normal(const std::filesystem::path &p) {
  std::error_code ec;
  const std::filesystem::path a = std::filesystem::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

}  // namespace

SourceLog::SourceLog(const std::filesystem::path &scene_dir)
    : base_(absolute_normal(scene_dir.empty() ? std::filesystem::path(".") : scene_dir)) {}

void SourceLog::record(const std::filesystem::path &path, std::string_view bytes) {
  const std::filesystem::path full = absolute_normal(path);
  std::error_code ec;
  const std::filesystem::path canonical = std::filesystem::weakly_canonical(full, ec);
  if (!seen_.insert(ec ? full : canonical).second) return;
  const std::filesystem::path relative = full.lexically_relative(base_);
  const bool below = !relative.empty() && *relative.begin() != "..";
  files_.push_back({(below ? relative : full).string(), content_hash(bytes), bytes.size()});
}

void SourceLog::record_scene(const std::string &name, std::string_view bytes) {
  files_.insert(files_.begin(), SourceFile{name, content_hash(bytes), bytes.size()});
}

Expected<std::string> read_source_file(const std::filesystem::path &path, SourceLog *log) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return Error{"is a directory"};
  errno = 0;
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{errno != 0 ? std::strerror(errno) : "cannot open"};
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return Error{"read error"};
  if (log) log->record(path, text.view());
  return text.str();
}

}  // namespace nimbus
