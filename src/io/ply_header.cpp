#include "io/ply_header.h"

#include <utility>

#include "io/text_cursor.h"

namespace mcon::io {
namespace {

bool parse_type(std::string_view name, PlyType& type) {
  static const std::pair<const char*, PlyType> names[] = {
      {"char", PlyType::Int8},     {"int8", PlyType::Int8},       {"uchar", PlyType::UInt8},
      {"uint8", PlyType::UInt8},   {"short", PlyType::Int16},     {"int16", PlyType::Int16},
      {"ushort", PlyType::UInt16}, {"uint16", PlyType::UInt16},   {"int", PlyType::Int32},
      {"int32", PlyType::Int32},   {"uint", PlyType::UInt32},     {"uint32", PlyType::UInt32},
      {"float", PlyType::Float32}, {"float32", PlyType::Float32}, {"double", PlyType::Float64},
      {"float64", PlyType::Float64}};
  for (const auto& [n, t] : names)
    if (name == n) {
      type = t;
      return true;
    }
  return false;
}

PlyType read_type(TextCursor& in) {
  const std::string_view word = in.word();
  PlyType type;
  if (!parse_type(word, type)) in.error("unknown PLY property type '" + TextCursor::printable(word) + "'");
  return type;
}

}  // namespace

std::size_t ply_type_size(PlyType type) {
  switch (type) {
    case PlyType::Int8:
    case PlyType::UInt8: return 1;
    case PlyType::Int16:
    case PlyType::UInt16: return 2;
    case PlyType::Int32:
    case PlyType::UInt32:
    case PlyType::Float32: return 4;
    case PlyType::Float64: return 8;
  }
  return 0;
}

bool ply_type_is_integer(PlyType type) { return type != PlyType::Float32 && type != PlyType::Float64; }

PlyHeader parse_ply_header(std::string_view data, const std::string& file_name) {
  TextCursor in(data, file_name);
  if (in.word() != "ply" || !in.at_line_end()) in.error("not a PLY file (it must start with a 'ply' line)");
  in.next_line();
  PlyHeader header;
  bool have_format = false;
  for (;;) {
    if (in.at_end()) in.error("the PLY header has no end_header line");
    const std::string_view keyword = in.word();
    if (keyword == "format") {
      const std::string_view format = in.word();
      if (format == "ascii") header.format = PlyFormat::Ascii;
      else if (format == "binary_little_endian") header.format = PlyFormat::BinaryLittleEndian;
      else if (format == "binary_big_endian") header.format = PlyFormat::BinaryBigEndian;
      else in.error("unknown PLY format '" + TextCursor::printable(format) + "'");
      const std::string_view version = in.word();
      if (version != "1.0" && version != "1") in.error("unsupported PLY version '" + TextCursor::printable(version) + "'");
      have_format = true;
    } else if (keyword == "element") {
      PlyElement element;
      element.name = std::string(in.word());
      if (element.name.empty()) in.error("element without a name");
      if (!in.read_integer(element.count) || element.count < 0)
        in.error("element '" + TextCursor::printable(element.name) + "' needs a non-negative count");
      header.elements.push_back(std::move(element));
    } else if (keyword == "property") {
      if (header.elements.empty()) in.error("property before any element");
      PlyProperty property;
      const std::string_view kind = in.word();
      if (kind == "list") {
        property.is_list = true;
        property.count_type = read_type(in);
        if (!ply_type_is_integer(property.count_type)) in.error("a PLY list count must have an integer type");
        property.type = read_type(in);
      } else if (!parse_type(kind, property.type)) {
        in.error("unknown PLY property type '" + TextCursor::printable(kind) + "'");
      }
      property.name = std::string(in.word());
      if (property.name.empty()) in.error("property without a name");
      header.elements.back().properties.push_back(std::move(property));
    } else if (keyword == "end_header") {
      if (!in.at_line_end()) in.error("unexpected text after end_header");
      in.next_line();
      break;
    } else if (keyword != "comment" && keyword != "obj_info" && !keyword.empty()) {
      in.error("unknown PLY header line '" + TextCursor::printable(keyword) + "'");
    }
    if (keyword != "comment" && keyword != "obj_info" && !in.at_line_end())
      in.error("unexpected " + in.quote_here() + " in the PLY header");
    in.next_line();
  }
  if (!have_format) in.error("the PLY header has no format line");
  header.data_offset = in.position();
  header.data_line = in.line();
  return header;
}

}  // namespace mcon::io
