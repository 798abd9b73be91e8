#include "film/exr_write.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfThreading.h>

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

#include "core/one_line.hpp"

namespace nimbus {
namespace {

Expected<Imf::Compression> compression_named(const std::string &name) {
  static const std::pair<const char *, Imf::Compression> kNames[] = {
      {"none", Imf::NO_COMPRESSION},  {"rle", Imf::RLE_COMPRESSION},   {"zips", Imf::ZIPS_COMPRESSION},
      {"zip", Imf::ZIP_COMPRESSION},  {"piz", Imf::PIZ_COMPRESSION},   {"pxr24", Imf::PXR24_COMPRESSION},
      {"b44", Imf::B44_COMPRESSION},  {"b44a", Imf::B44A_COMPRESSION}, {"dwaa", Imf::DWAA_COMPRESSION},
      {"dwab", Imf::DWAB_COMPRESSION}};
  for (const auto &[n, c] : kNames)
    if (name == n) return c;
  return Error{"unknown EXR compression '" + name + "'"};
}

Imf::PixelType exr_type(PixelType type) { return type == PixelType::UInt32 ? Imf::UINT : Imf::FLOAT; }

Expected<Imf::Header> header_of(const ImageDesc &desc, size_t index, bool multi_part) {
  if (desc.type == PixelType::UInt8) return Error{"EXR has no 8-bit channels"};
  Imf::Header header(desc.width, desc.height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const std::string &name : desc.channels)
    header.channels().insert(name, Imf::Channel(exr_type(desc.type)));
  std::string part_name = "part" + std::to_string(index);
  for (const ImageAttribute &a : desc.attributes) {
    if (a.name == "compression") {
      const Expected<Imf::Compression> c = compression_named(a.text);
      if (!c) return c.error();
      header.compression() = *c;
    } else if (a.name == "name") {
      part_name = a.text;
    } else if (a.kind == ImageAttribute::Kind::String) {
      header.insert(a.name, Imf::StringAttribute(a.text));
    } else if (a.kind == ImageAttribute::Kind::Int) {
      header.insert(a.name, Imf::IntAttribute(int(a.number)));
    } else {
      header.insert(a.name, Imf::DoubleAttribute(a.number));
    }
  }
  if (multi_part) {
    header.setName(part_name);
    header.setType(Imf::SCANLINEIMAGE);
  }
  return header;
}

// The part's pixels as OpenEXR reads them: channel c of pixel (x, y) at pixels + ((y * width + x) * n + c)
// * 4.
Imf::FrameBuffer frame_buffer(const ImagePart &part) {
  const ImageDesc &d = part.desc;
  const size_t pixel = d.channels.size() * 4, row = pixel * size_t(d.width);
  char *base = const_cast<char *>(static_cast<const char *>(part.pixels));  // OpenEXR only reads it
  Imf::FrameBuffer fb;
  for (size_t c = 0; c < d.channels.size(); ++c)
    fb.insert(d.channels[c], Imf::Slice(exr_type(d.type), base + 4 * c, pixel, row));
  return fb;
}

}  // namespace

Status write_exr_file(const std::string &file, std::span<const ImagePart> parts) {
  std::vector<Imf::Header> headers;
  for (size_t i = 0; i < parts.size(); ++i) {
    Expected<Imf::Header> h = header_of(parts[i].desc, i, parts.size() > 1);
    if (!h) return h.error();
    headers.push_back(std::move(*h));
  }
  // Zip compression in as many threads as the machine has (OpenEXR's default is none but the caller's).
  static const int threads = [] {
    const int n = int(std::max(1u, std::thread::hardware_concurrency()));
    Imf::setGlobalThreadCount(n);
    return n;
  }();
  try {
    if (parts.size() == 1) {
      Imf::OutputFile out(file.c_str(), headers[0], threads);
      out.setFrameBuffer(frame_buffer(parts[0]));
      out.writePixels(parts[0].desc.height);
    } else {
      Imf::MultiPartOutputFile out(file.c_str(), headers.data(), int(headers.size()), false, threads);
      for (size_t i = 0; i < parts.size(); ++i) {
        Imf::OutputPart part(out, int(i));
        part.setFrameBuffer(frame_buffer(parts[i]));
        part.writePixels(parts[i].desc.height);
      }
    }
  } catch (const std::exception &e) {
    return Error{one_line(e.what())};
  }
  return Ok{};
}

}  // namespace nimbus
