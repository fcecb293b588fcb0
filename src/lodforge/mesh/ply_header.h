#pragma once
/// The header of a PLY file (Turk, "The PLY Polygon File Format", 1994) as
/// the readers of mesh/ see it: its encoding, and each element's count and
/// properties with the role each plays. Shared by the in-memory reader
/// (mesh_io_ply.cpp) and the streaming one (triangle_stream.cpp). Not part
/// of the public API.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "lodforge/core/log.h"

namespace lodforge::detail::ply {

enum class PlyType : std::uint8_t {
  kInt8,
  kUint8,
  kInt16,
  kUint16,
  kInt32,
  kUint32,
  kFloat32,
  kFloat64
};

struct TypeInfo {
  std::string_view names[2];
  PlyType type;
  int size;
};
inline constexpr TypeInfo kTypes[] = {
    {{"char", "int8"}, PlyType::kInt8, 1},        {{"uchar", "uint8"}, PlyType::kUint8, 1},
    {{"short", "int16"}, PlyType::kInt16, 2},     {{"ushort", "uint16"}, PlyType::kUint16, 2},
    {{"int", "int32"}, PlyType::kInt32, 4},       {{"uint", "uint32"}, PlyType::kUint32, 4},
    {{"float", "float32"}, PlyType::kFloat32, 4}, {{"double", "float64"}, PlyType::kFloat64, 8},
};

inline int type_size(PlyType t) {
  return kTypes[static_cast<int>(t)].size;
}
inline bool is_float(PlyType t) {
  return t == PlyType::kFloat32 || t == PlyType::kFloat64;
}

// Roles; the first kSlots index a per-item value array.
enum Role : std::uint8_t {
  kX,
  kY,
  kZ,
  kNx,
  kNy,
  kNz,
  kRed,
  kGreen,
  kBlue,
  kU,
  kV,
  kMaterial,
  kVertex1,
  kVertex2,
  kSlots,
  kSkip = kSlots,
  kIndices,
  kStrip,
};

enum class ElementKind { kVertex, kFace, kTristrips, kEdge, kOther };

struct Property {
  std::string name;
  PlyType type = PlyType::kFloat32;
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
  Role role = kSkip;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  ElementKind kind = ElementKind::kOther;
  std::vector<Property> props;
  int line = 0;
  std::uint64_t roles_taken = 0;  ///< bit r: a property has role r already
};

enum class Encoding { kAscii, kLittle, kBig };

struct Header {
  Encoding encoding = Encoding::kAscii;
  std::vector<Element> elements;
  std::size_t body = 0;  // byte offset of the data
};

/// Parses the header at the start of `data` (which may hold more than the
/// header: only up to the line after 'end_header' is read). Throws
/// ParseError (file:line:col) for a malformed header; warns on `log` (may be
/// null) about elements it skips.
Header parse_header(std::string_view data, const std::string& file, Log* log);

}  // namespace lodforge::detail::ply
