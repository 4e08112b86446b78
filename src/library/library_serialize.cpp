// ConstraintLibrary -> FlatBuffer (schema/macrocon_library.fbs), and the atomic save on top.
#include <string>

#include "base/atomic_file.h"
#include "base/error.h"
#include "library/library_file.h"
#include "macrocon_library_generated.h"

namespace mcon {
namespace {

namespace fb = mcon::fb;
using flatbuffers::FlatBufferBuilder;
using flatbuffers::Offset;

// An upper bound on the finished buffer: payload bytes plus a generous allowance per object
// (vtable, offsets, alignment padding). FlatBufferBuilder cannot grow past 2 GiB (it only asserts
// in debug builds), so the caller checks this bound first.
std::size_t polyline_bound(const ConstraintPolyline& p) { return 128 + p.points.size() * (4 + 24); }

std::size_t size_bound(const ConstraintLibrary& lib) {
  const RetrievalConfig& c = lib.retrieval();
  std::size_t bytes = 1024 + lib.name().size() + lib.description().size() + c.descriptor.size() +
                      8 * (c.normalization_mean.size() + c.normalization_scale.size() + c.vocabulary.size());
  for (const MacroConstraint& e : lib.entries()) {
    bytes += 512 + e.name.size() + e.class_label.size() + e.author.size() + e.licence.size();
    for (const std::string& t : e.tags) bytes += 32 + t.size();
    bytes += 4 * (e.positions.size() + e.triangles.size() + e.descriptors.size() + e.histogram.size());
    for (const auto& p : e.guides) bytes += polyline_bound(p);
    for (const auto& p : e.features) bytes += polyline_bound(p);
    bytes += e.singularities.size() * 96;
    for (const VertexField& f : e.fields) bytes += 96 + f.name.size() + 4 * (f.values.size() + f.labels.size());
  }
  return bytes;
}

Offset<fb::Polyline> write_polyline(FlatBufferBuilder& b, const ConstraintPolyline& line) {
  std::vector<std::uint32_t> faces;
  std::vector<double> barycentrics;
  faces.reserve(line.points.size());
  barycentrics.reserve(3 * line.points.size());
  for (const SurfacePoint& p : line.points) {
    faces.push_back(static_cast<std::uint32_t>(p.triangle));
    barycentrics.insert(barycentrics.end(), p.barycentric.data(), p.barycentric.data() + 3);
  }
  return fb::CreatePolyline(b, b.CreateVector(faces), b.CreateVector(barycentrics), line.closed);
}

flatbuffers::Offset<flatbuffers::Vector<Offset<fb::Polyline>>> write_polylines(
    FlatBufferBuilder& b, const std::vector<ConstraintPolyline>& lines) {
  std::vector<Offset<fb::Polyline>> offsets;
  for (const ConstraintPolyline& line : lines) offsets.push_back(write_polyline(b, line));
  return b.CreateVector(offsets);
}

Offset<fb::Entry> write_entry(FlatBufferBuilder& b, const MacroConstraint& e) {
  const auto name = b.CreateString(e.name);
  const auto class_label = b.CreateString(e.class_label);
  std::vector<Offset<fb::Tag>> tag_offsets;
  for (const std::string& t : e.tags) tag_offsets.push_back(fb::CreateTag(b, b.CreateString(t)));
  const auto tags = b.CreateVector(tag_offsets);
  const auto author = b.CreateString(e.author);
  const auto licence = b.CreateString(e.licence);
  const auto positions = b.CreateVector(e.positions);
  const auto triangles = b.CreateVector(e.triangles);
  const auto center_barycentric = b.CreateVector(e.center.barycentric.data(), 3);
  const auto source_origin = b.CreateVector(e.source_origin.data(), 3);
  const auto guides = write_polylines(b, e.guides);
  const auto features = write_polylines(b, e.features);
  std::vector<Offset<fb::Singularity>> singularity_offsets;
  for (const Singularity& s : e.singularities)
    singularity_offsets.push_back(fb::CreateSingularity(
        b, static_cast<std::uint32_t>(s.location.triangle), b.CreateVector(s.location.barycentric.data(), 3), s.index_quarters));
  const auto singularities = b.CreateVector(singularity_offsets);
  std::vector<Offset<fb::VertexField>> field_offsets;
  for (const VertexField& f : e.fields) {
    const auto field_name = b.CreateString(f.name);
    const auto values = f.values.empty() ? 0 : b.CreateVector(f.values);
    const auto labels = f.labels.empty() ? 0 : b.CreateVector(f.labels);
    field_offsets.push_back(fb::CreateVertexField(b, field_name, static_cast<fb::FieldKind>(f.kind), f.dimension,
                                                  values, labels));
  }
  const auto fields = b.CreateVector(field_offsets);
  const auto descriptors = b.CreateVector(e.descriptors);
  const auto histogram = b.CreateVector(e.histogram);
  const auto up = e.up ? b.CreateVector(e.up->data(), 3) : 0;  // absent: the bytes of a file without it

  fb::EntryBuilder eb(b);
  eb.add_id(e.id);
  eb.add_name(name);
  eb.add_class_label(class_label);
  eb.add_tags(tags);
  eb.add_author(author);
  eb.add_licence(licence);
  eb.add_positions(positions);
  eb.add_triangles(triangles);
  eb.add_center_face(static_cast<std::uint32_t>(e.center.triangle));
  eb.add_center_barycentric(center_barycentric);
  eb.add_source_scale(e.source_scale);
  eb.add_source_origin(source_origin);
  eb.add_guides(guides);
  eb.add_features(features);
  eb.add_singularities(singularities);
  eb.add_fields(fields);
  eb.add_descriptors(descriptors);
  eb.add_histogram(histogram);
  if (e.up) eb.add_up(up);
  return eb.Finish();
}

Offset<fb::RetrievalConfig> write_config(FlatBufferBuilder& b, const RetrievalConfig& c) {
  return fb::CreateRetrievalConfig(b, b.CreateString(c.descriptor), c.dimension, b.CreateVector(c.normalization_mean),
                                   b.CreateVector(c.normalization_scale), c.vocabulary_size,
                                   b.CreateVector(c.vocabulary), c.sigma_bof, c.rings, c.seed);
}

}  // namespace

std::vector<std::uint8_t> serialize_library(const ConstraintLibrary& library) {
  const std::size_t bound = size_bound(library);
  require(bound < kLibraryMaxBytes, MCON_ERROR_INVALID_ARGUMENT,
          "the library needs up to " + std::to_string(bound) + " bytes; one library file holds less than 2 GiB");
  FlatBufferBuilder b(bound);
  // Write every scalar, even when it equals the schema default: -0.0 == 0.0 would otherwise be
  // dropped and read back as +0.0, and the round trip must be bit-exact.
  b.ForceDefaults(true);
  const auto config = write_config(b, library.retrieval());
  std::vector<Offset<fb::Entry>> entry_offsets;
  entry_offsets.reserve(library.size());
  for (const MacroConstraint& e : library.entries()) entry_offsets.push_back(write_entry(b, e));
  const auto entries = b.CreateVector(entry_offsets);
  const auto name = b.CreateString(library.name());
  const auto description = b.CreateString(library.description());
  fb::LibraryBuilder lb(b);
  lb.add_format_version(kLibraryFormatVersion);
  lb.add_name(name);
  lb.add_description(description);
  lb.add_retrieval(config);
  lb.add_entries(entries);
  lb.add_content_checksum(0);  // written (ForceDefaults), then filled in by seal_library_buffer
  fb::FinishLibraryBuffer(b, lb.Finish());
  std::vector<std::uint8_t> bytes(b.GetBufferPointer(), b.GetBufferPointer() + b.GetSize());
  seal_library_buffer(bytes);
  return bytes;
}

void save_library_atomic(const ConstraintLibrary& library, const std::string& path) {
  const std::vector<std::uint8_t> bytes = serialize_library(library);
  write_file_atomic(path, bytes.data(), bytes.size());
}

}  // namespace mcon
