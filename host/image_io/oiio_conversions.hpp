// Between the image I/O interface's records (core/image_io.hpp) and OpenImageIO's.
#pragma once

#include <OpenImageIO/imageio.h>

#include "core/image_io.hpp"

namespace nimbus {

inline OIIO::TypeDesc type_desc(PixelType type) {
  switch (type) {
    case PixelType::UInt8:
      return OIIO::TypeDesc::UINT8;
    case PixelType::UInt32:
      return OIIO::TypeDesc::UINT;
    case PixelType::Float:
      break;
  }
  return OIIO::TypeDesc::FLOAT;
}

// A scalar number of any base type as a double (integers exactly up to 2^53); false for anything else.
inline bool scalar_number(const OIIO::ParamValue &p, double &v) {
  const OIIO::TypeDesc t = p.type();
  if (t.aggregate != OIIO::TypeDesc::SCALAR || t.arraylen != 0 || p.nvalues() != 1) return false;
  switch (t.basetype) {
    case OIIO::TypeDesc::INT8:
      v = p.get<int8_t>();
      return true;
    case OIIO::TypeDesc::UINT8:
      v = p.get<uint8_t>();
      return true;
    case OIIO::TypeDesc::INT16:
      v = p.get<int16_t>();
      return true;
    case OIIO::TypeDesc::UINT16:
      v = p.get<uint16_t>();
      return true;
    case OIIO::TypeDesc::INT32:
      v = p.get<int32_t>();
      return true;
    case OIIO::TypeDesc::UINT32:
      v = p.get<uint32_t>();
      return true;
    case OIIO::TypeDesc::INT64:
      v = static_cast<double>(p.get<int64_t>());
      return true;
    case OIIO::TypeDesc::UINT64:
      v = static_cast<double>(p.get<uint64_t>());
      return true;
    case OIIO::TypeDesc::HALF:
      v = p.get_float();
      return true;
    case OIIO::TypeDesc::FLOAT:
      v = p.get<float>();
      return true;
    case OIIO::TypeDesc::DOUBLE:
      v = p.get<double>();
      return true;
    default:
      return false;
  }
}

inline ImageDesc desc_of(const OIIO::ImageSpec &spec) {
  ImageDesc d;
  d.x = spec.x, d.y = spec.y, d.z = spec.z;
  d.width = spec.width, d.height = spec.height, d.depth = spec.depth;
  d.tile_width = spec.tile_width, d.tile_height = spec.tile_height;
  for (int c = 0; c < spec.nchannels; ++c) d.channels.push_back(spec.channel_name(c));
  d.floating_point = spec.format.is_floating_point();
  for (const OIIO::ParamValue &p : spec.extra_attribs) {
    ImageAttribute a;
    a.name = p.name().string();
    if (p.type() == OIIO::TypeString) {
      a.text = p.get<OIIO::ustring>().string();
    } else if (scalar_number(p, a.number)) {
      a.kind = ImageAttribute::Kind::Double;
    } else {
      continue;
    }
    d.attributes.push_back(std::move(a));
  }
  return d;
}

}  // namespace nimbus
