#include "film/film.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace nimbus {
namespace {

// Lower-case segments of [a-z0-9_] joined by single dots: the dots become EXR layer separators, so an
// empty segment would make a layer name readers split differently.
bool valid_element_name(std::string_view name) {
  if (name.empty() || name.size() > 200 || name.front() == '.' || name.back() == '.') return false;
  char previous = 0;
  for (char c : name) {
    const bool word = (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
    if (!word && !(c == '.' && previous != '.')) return false;
    previous = c;
  }
  return true;
}

}  // namespace

Film::Film(uint32_t width, uint32_t height) : width_(width), height_(height) {
  elements_.emplace_back("beauty", 3, kSplat);
  activate(elements_[kBeauty]);
}

int32_t Film::register_element(std::string_view name, uint32_t channels, uint32_t flags) {
  if (!valid_element_name(name) || (channels != 1 && channels != 3) || (flags & ~kSplat) != 0)
    return kInvalid;
  for (size_t i = 0; i < elements_.size(); ++i) {
    if (elements_[i].name != name) continue;
    if (elements_[i].channels != channels) return kInvalid;
    // Two plugins may declare the same element, only one of them splatting into it.
    elements_[i].flags |= flags;
    return static_cast<int32_t>(i);
  }
  elements_.emplace_back(name, channels, flags);
  return static_cast<int32_t>(elements_.size() - 1);
}

void Film::request(std::string_view name) {
  if (std::find(requested_.begin(), requested_.end(), name) == requested_.end())
    requested_.emplace_back(name);
}

Status Film::allocate() {
  std::vector<std::string> unknown;
  for (const std::string &name : requested_) {
    const bool known =
        std::any_of(elements_.begin(), elements_.end(), [&](const Element &e) { return e.name == name; });
    if (!known) unknown.push_back(name);
  }
  if (!unknown.empty()) {
    std::vector<std::string> names;
    for (const Element &e : elements_) names.push_back(e.name);
    std::sort(names.begin(), names.end());
    std::string message = unknown.size() == 1 ? "unknown render element " : "unknown render elements ";
    for (size_t i = 0; i < unknown.size(); ++i) message += (i ? ", '" : "'") + unknown[i] + "'";
    message += " (available: ";
    for (size_t i = 0; i < names.size(); ++i) message += (i ? ", " : "") + names[i];
    return Error{message + ")"};
  }
  for (Element &e : elements_) {
    if (!e.active && std::find(requested_.begin(), requested_.end(), e.name) != requested_.end()) activate(e);
  }
  return Ok{};
}

void Film::activate(Element &e) {
  e.active = true;
  e.sum.assign(pixel_count() * e.channels, 0.0);
  if (e.flags & kSplat) e.workers = std::vector<WorkerSplats>(worker_count_);
}

void Film::set_worker_count(uint32_t workers) {
  merge_splats();
  worker_count_ = std::max(1u, workers);
  for (Element &e : elements_) {
    if (e.active && (e.flags & kSplat)) e.workers.resize(worker_count_);
  }
}

std::vector<int32_t> Film::active_elements() const {
  std::vector<int32_t> ids;
  for (size_t i = 0; i < elements_.size(); ++i) {
    if (elements_[i].active) ids.push_back(static_cast<int32_t>(i));
  }
  return ids;
}

size_t Film::allocated_bytes() const {
  size_t bytes = 0;
  for (const Element &e : elements_) {
    bytes += e.sum.capacity() * sizeof(double) + e.workers.capacity() * sizeof(WorkerSplats);
    for (const WorkerSplats &w : e.workers) bytes += w.sum.capacity() * sizeof(double);
  }
  return bytes;
}

void Film::accumulate(int32_t el, uint32_t x, uint32_t y, const float *v) {
  if (!is_active(el) || x >= width_ || y >= height_) return;
  Element &e = elements_[el];
  const uint32_t channels = e.channels;
  for (uint32_t c = 0; c < channels; ++c) {
    if (!std::isfinite(v[c])) {
      nonfinite_.fetch_add(1, std::memory_order_relaxed);
      return;
    }
  }
  double *p = e.sum.data() + (size_t(y) * width_ + x) * channels;
  for (uint32_t c = 0; c < channels; ++c) p[c] += v[c];
}

void Film::splat(uint32_t worker, int32_t el, float fx, float fy, const float *v) {
  if (!is_active(el)) return;
  Element &e = elements_[el];
  if (!(e.flags & kSplat) || worker >= e.workers.size()) return;
  const uint32_t channels = e.channels;
  bool finite = std::isfinite(fx) && std::isfinite(fy);
  for (uint32_t c = 0; c < channels; ++c) finite = finite && std::isfinite(v[c]);
  if (!finite) {
    nonfinite_.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (!(fx >= 0 && fy >= 0 && fx < float(width_) && fy < float(height_))) return;
  const uint32_t x = std::min(static_cast<uint32_t>(fx), width_ - 1);
  const uint32_t y = std::min(static_cast<uint32_t>(fy), height_ - 1);
  if (x < region_[0] || y < region_[1] || x >= region_[2] || y >= region_[3]) return;
  WorkerSplats &w = e.workers[worker];
  // Only this worker touches slot `worker`, so allocating here races with nobody.
  if (w.sum.empty()) w.sum.assign(pixel_count() * channels, 0.0);
  if (!w.dirty) w.dirty = true;
  double *p = w.sum.data() + (size_t(y) * width_ + x) * channels;
  for (uint32_t c = 0; c < channels; ++c) p[c] += v[c];
}

void Film::merge_splats() {
  for (Element &e : elements_) {
    std::vector<WorkerSplats *> dirty;
    for (WorkerSplats &w : e.workers) {
      if (w.dirty) dirty.push_back(&w);
    }
    if (dirty.empty()) continue;
    // Each value's summation order is fixed (worker index order), so splitting rows over threads is
    // deterministic.
    const size_t row = size_t(width_) * e.channels;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, height_),
                      [&](const tbb::blocked_range<uint32_t> &rows) {
                        for (size_t i = rows.begin() * row; i < rows.end() * row; ++i) {
                          double s = 0;
                          for (WorkerSplats *w : dirty) {
                            s += w->sum[i];
                            w->sum[i] = 0;
                          }
                          e.sum[i] += s;
                        }
                      });
    for (WorkerSplats *w : dirty) w->dirty = false;
  }
}

void Film::discard_splats() {
  for (Element &e : elements_)
    for (WorkerSplats &w : e.workers)
      if (w.dirty) {
        std::fill(w.sum.begin(), w.sum.end(), 0.0);
        w.dirty = false;
      }
}

std::unique_ptr<Film> Film::snapshot() const {
  auto copy = std::make_unique<Film>(width_, height_);
  copy->elements_.clear();
  for (const Element &e : elements_) {
    copy->elements_.emplace_back(e.name, e.channels, e.flags);
    copy->elements_.back().active = e.active;
    copy->elements_.back().sum = e.sum;
  }
  copy->requested_ = requested_;
  copy->iterations_ = iterations_;
  copy->nonfinite_.store(nonfinite_count());
  return copy;
}

bool Film::has_pending_splats() const {
  for (const Element &e : elements_) {
    for (const WorkerSplats &w : e.workers) {
      if (w.dirty) return true;
    }
  }
  return false;
}

std::span<const double> Film::sums(int32_t el) const {
  if (!is_active(el)) return {};
  return elements_[el].sum;
}

std::span<double> Film::sums(int32_t el) {
  if (!is_active(el)) return {};
  return elements_[el].sum;
}

std::vector<float> Film::resolve(int32_t el) const {
  if (!is_active(el)) return {};
  const Element &e = elements_[el];
  std::vector<float> image(e.sum.size(), 0.0f);
  if (iterations_ == 0) return image;
  // Divide rather than multiply by 1/N: one rounding instead of two, so a constant signal resolves exactly.
  const double n = static_cast<double>(iterations_);
  for (size_t i = 0; i < image.size(); ++i) image[i] = static_cast<float>(e.sum[i] / n);
  return image;
}

}  // namespace nimbus
