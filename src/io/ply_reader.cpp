// PLY body: vertex x, y, z of any scalar type (and, when asked, the vertex element's other scalar
// properties) and the face `vertex_indices` (or `vertex_index`) list of any integer type, in
// ASCII or either binary byte order. Every other element and property is read past according to
// its declared type, so unknown data never shifts the rest.
#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstring>

#include "io/ply_header.h"
#include "io/polygon_soup.h"
#include "io/text_cursor.h"

namespace mcon::io {
namespace {

// Binary values with bounds checks and optional byte swapping.
class BinarySource {
 public:
  BinarySource(std::string_view data, std::size_t offset, bool swap, const std::string& file_name)
      : data_(data), pos_(offset), swap_(swap), file_name_(file_name) {}

  double read_real(PlyType type) {
    switch (type) {
      case PlyType::Int8: return raw<std::int8_t>();
      case PlyType::UInt8: return raw<std::uint8_t>();
      case PlyType::Int16: return raw<std::int16_t>();
      case PlyType::UInt16: return raw<std::uint16_t>();
      case PlyType::Int32: return raw<std::int32_t>();
      case PlyType::UInt32: return raw<std::uint32_t>();
      case PlyType::Float32: return static_cast<double>(raw<float>());
      case PlyType::Float64: return raw<double>();
    }
    return 0;
  }
  long long read_integer(PlyType type) { return static_cast<long long>(read_real(type)); }  // exact below 2^53
  // A list count, checked against the bytes left so garbage cannot start a huge loop.
  long long read_list_count(PlyType count_type, PlyType item_type) {
    const long long n = read_integer(count_type);
    if (n < 0) error("negative list count " + std::to_string(n));
    if (static_cast<unsigned long long>(n) > (data_.size() - pos_) / ply_type_size(item_type))
      error("truncated data (a list of " + std::to_string(n) + " items runs past the end of the file)");
    return n;
  }
  [[noreturn]] void error(const std::string& message) const {
    fail(MCON_ERROR_IO, file_name_ + ": byte " + std::to_string(pos_) + ": " + message);
  }

 private:
  template <typename T>
  T raw() {
    if (data_.size() - pos_ < sizeof(T)) error("truncated binary PLY data");
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, data_.data() + pos_, sizeof(T));
    if (swap_) std::reverse(bytes, bytes + sizeof(T));
    pos_ += sizeof(T);
    T value;
    std::memcpy(&value, bytes, sizeof(T));
    return value;
  }

  std::string_view data_;
  std::size_t pos_;
  bool swap_;
  const std::string& file_name_;
};

// ASCII values: whitespace-separated tokens (element instances need not be one per line).
class AsciiSource {
 public:
  AsciiSource(std::string_view data, std::size_t offset, int line, const std::string& file_name)
      : in_(data, file_name, offset, line), size_(data.size()) {}

  double read_real(PlyType type) {
    in_.skip_space(false);
    if (ply_type_is_integer(type)) return static_cast<double>(read_integer(type));
    double value = 0;
    if (!in_.read_double(value)) in_.error("expected a number, found " + in_.quote_here());
    return value;
  }
  long long read_integer(PlyType) {
    in_.skip_space(false);
    long long value = 0;
    if (!in_.read_integer(value)) in_.error("expected an integer, found " + in_.quote_here());
    return value;
  }
  long long read_list_count(PlyType count_type, PlyType) {
    const long long n = read_integer(count_type);
    if (n < 0 || static_cast<unsigned long long>(n) > size_) error("invalid list count " + std::to_string(n));
    return n;
  }
  [[noreturn]] void error(const std::string& message) const { in_.error(message); }

 private:
  TextCursor in_;
  std::size_t size_;
};

int find_property(const PlyElement& element, std::initializer_list<const char*> names) {
  for (const char* name : names)
    for (std::size_t p = 0; p < element.properties.size(); ++p)
      if (element.properties[p].name == name) return static_cast<int>(p);
  return -1;
}

template <typename Source>
void skip_property(Source& in, const PlyProperty& property) {
  if (!property.is_list) {
    in.read_real(property.type);
    return;
  }
  const long long n = in.read_list_count(property.count_type, property.type);
  for (long long k = 0; k < n; ++k) in.read_real(property.type);
}

template <typename Source>
void read_vertices(Source& in, const PlyElement& element, const std::string& file_name, bool keep_properties,
                   PolygonSoup& soup) {
  int axis_property[3];
  const char* axis_names[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    axis_property[a] = find_property(element, {axis_names[a]});
    if (axis_property[a] < 0 || element.properties[axis_property[a]].is_list)
      fail(MCON_ERROR_IO, file_name + ": the PLY vertex element has no scalar property '" + axis_names[a] + "'");
  }
  auto is_axis = [&](int p) { return p == axis_property[0] || p == axis_property[1] || p == axis_property[2]; };
  if (keep_properties)
    for (int p = 0; p < static_cast<int>(element.properties.size()); ++p)
      if (!is_axis(p) && !element.properties[p].is_list) soup.vertex_property_names.push_back(element.properties[p].name);
  for (long long v = 0; v < element.count; ++v) {
    Vec3 position;
    for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
      const PlyProperty& property = element.properties[p];
      const int axis = p == axis_property[0] ? 0 : p == axis_property[1] ? 1 : p == axis_property[2] ? 2 : -1;
      if (axis >= 0) position[axis] = in.read_real(property.type);
      else if (keep_properties && !property.is_list) soup.vertex_property_values.push_back(in.read_real(property.type));
      else skip_property(in, property);
    }
    soup.positions.push_back(position);
  }
}

template <typename Source>
void read_faces(Source& in, const PlyElement& element, long long vertex_count, const std::string& file_name,
                PolygonSoup& soup) {
  const int list = find_property(element, {"vertex_indices", "vertex_index"});
  if (list < 0 || !element.properties[list].is_list || !ply_type_is_integer(element.properties[list].type))
    fail(MCON_ERROR_IO, file_name + ": the PLY face element has no integer list property 'vertex_indices'");
  for (long long f = 0; f < element.count; ++f) {
    for (int p = 0; p < static_cast<int>(element.properties.size()); ++p) {
      const PlyProperty& property = element.properties[p];
      if (p != list) {
        skip_property(in, property);
        continue;
      }
      const long long n = in.read_list_count(property.count_type, property.type);
      if (n < 3) in.error("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (at least 3 needed)");
      for (long long k = 0; k < n; ++k) {
        const long long index = in.read_integer(property.type);
        if (index < 0 || index >= vertex_count)
          in.error("face " + std::to_string(f) + " uses vertex index " + std::to_string(index) +
                   " but the file has " + std::to_string(vertex_count) + " vertices");
        soup.corners.push_back(static_cast<int>(index));
      }
      if (soup.corners.size() > static_cast<std::size_t>(INT_MAX)) in.error("too many face corners");
      soup.face_start.push_back(static_cast<int>(soup.corners.size()));
    }
  }
}

template <typename Source>
PolygonSoup read_body(Source& in, const PlyHeader& header, std::size_t data_size, const std::string& file_name,
                      bool keep_vertex_properties) {
  const PlyElement* vertices = nullptr;
  for (const PlyElement& element : header.elements) {
    if (element.name != "vertex") continue;
    if (vertices) fail(MCON_ERROR_IO, file_name + ": the PLY header has two vertex elements");
    vertices = &element;
  }
  if (!vertices) fail(MCON_ERROR_IO, file_name + ": the PLY header has no vertex element");
  for (const PlyElement& element : header.elements)
    if ((element.name == "vertex" || element.name == "face") && element.count > INT_MAX - 1)
      fail(MCON_ERROR_IO, file_name + ": too many " + element.name + "s (" + std::to_string(element.count) + ")");

  PolygonSoup soup;
  // Every value takes at least one byte, so a bogus count cannot force a huge reservation.
  soup.positions.reserve(static_cast<std::size_t>(std::min<long long>(vertices->count, data_size / 3)));
  bool have_faces = false;
  for (const PlyElement& element : header.elements) {
    if (&element == vertices) {
      read_vertices(in, element, file_name, keep_vertex_properties, soup);
    } else if (element.properties.empty()) {
      continue;  // no data at all, whatever the count
    } else if (element.name == "face" && !have_faces) {
      read_faces(in, element, vertices->count, file_name, soup);
      have_faces = true;
    } else {
      for (long long i = 0; i < element.count; ++i)
        for (const PlyProperty& property : element.properties) skip_property(in, property);
    }
  }
  return soup;
}

}  // namespace

PolygonSoup parse_ply(std::string_view data, const std::string& file_name, bool keep_vertex_properties) {
  const PlyHeader header = parse_ply_header(data, file_name);
  if (header.format == PlyFormat::Ascii) {
    AsciiSource in(data, header.data_offset, header.data_line, file_name);
    return read_body(in, header, data.size(), file_name, keep_vertex_properties);
  }
  const std::uint16_t probe = 1;
  unsigned char first_byte;
  std::memcpy(&first_byte, &probe, 1);
  const bool host_little_endian = first_byte == 1;
  const bool file_little_endian = header.format == PlyFormat::BinaryLittleEndian;
  BinarySource in(data, header.data_offset, host_little_endian != file_little_endian, file_name);
  return read_body(in, header, data.size(), file_name, keep_vertex_properties);
}

}  // namespace mcon::io
