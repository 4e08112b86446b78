// The PLY header (http://paulbourke.net/dataformats/ply/): format, elements in file order and
// their scalar or list properties. The body reader needs all of it to skip what it does not use.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mcon::io {

enum class PlyType { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
enum class PlyFormat { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::Float32;  // the item type for a list
  bool is_list = false;
  PlyType count_type = PlyType::UInt8;  // lists only; always an integer type
};

struct PlyElement {
  std::string name;
  long long count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  PlyFormat format = PlyFormat::Ascii;
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // first byte after the end_header line
  int data_line = 1;            // its line number (for ASCII error messages)
};

std::size_t ply_type_size(PlyType type);
bool ply_type_is_integer(PlyType type);

// Throws mcon::Error(MCON_ERROR_IO) naming the file and header line on anything malformed.
PlyHeader parse_ply_header(std::string_view data, const std::string& file_name);

}  // namespace mcon::io
