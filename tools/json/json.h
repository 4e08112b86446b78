// A small, strict JSON value (RFC 8259) for the benchmark specs the evaluation commands read and the
// result files they write. Strict on input (no comments, trailing commas, leading zeros, control
// characters, invalid UTF-8, lone surrogates or duplicate keys; errors name the byte offset, line
// and column) and on output (NaN and infinities are rejected; doubles are printed with the
// shortest text that reads back to the same bits, so a write/parse round trip is exact).
//
// Its own static library (macrocon_json) with no link dependency on the core: the starter library
// generator, which uses only the public C API, shares it with the tools. File I/O (gzip through the
// SDK's io layer) lives in tools/common/json.h.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace mcon::tools {

class Json {
 public:
  enum class Type { Null, Bool, Number, String, Array, Object };

  Json() = default;  // null
  Json(std::nullptr_t) {}
  Json(bool value) : type_(Type::Bool), bool_(value) {}
  Json(double value) : type_(Type::Number), number_(value) {}
  Json(int value) : Json(static_cast<double>(value)) {}
  Json(long value) : Json(static_cast<double>(value)) {}
  Json(long long value) : Json(static_cast<double>(value)) {}
  Json(unsigned value) : Json(static_cast<double>(value)) {}
  Json(unsigned long value) : Json(static_cast<double>(value)) {}
  Json(std::string value) : type_(Type::String), string_(std::move(value)) {}
  Json(const char* value) : Json(std::string(value)) {}
  static Json array() { return Json(Type::Array); }
  static Json object() { return Json(Type::Object); }

  Type type() const { return type_; }
  bool is_null() const { return type_ == Type::Null; }
  bool is_bool() const { return type_ == Type::Bool; }
  bool is_number() const { return type_ == Type::Number; }
  bool is_string() const { return type_ == Type::String; }
  bool is_array() const { return type_ == Type::Array; }
  bool is_object() const { return type_ == Type::Object; }

  // Typed access; a wrong type throws mcon::Error(MCON_ERROR_INVALID_ARGUMENT).
  bool as_bool() const;
  double as_number() const;
  long long as_int() const;  // the number must be integral and within +-2^53
  const std::string& as_string() const;

  // Arrays and objects: number of elements or members.
  std::size_t size() const;
  // Array elements (index checked).
  const Json& operator[](std::size_t index) const;
  Json& operator[](std::size_t index);
  const std::vector<Json>& elements() const;  // array only
  void push_back(Json value);                 // array only

  // Object members keep their insertion (file) order.
  const std::string& key(std::size_t index) const;    // object only
  const Json& value(std::size_t index) const;         // object only
  const Json* find(std::string_view key) const;       // nullptr if absent
  bool contains(std::string_view key) const { return find(key) != nullptr; }
  const Json& at(std::string_view key) const;         // absent: mcon::Error(MCON_ERROR_NOT_FOUND)
  Json& set(std::string key, Json value);             // insert or replace; returns the member

  bool operator==(const Json& other) const;
  bool operator!=(const Json& other) const { return !(*this == other); }

 private:
  explicit Json(Type type) : type_(type) {}
  void expect(Type type, const char* what) const;

  Type type_ = Type::Null;
  bool bool_ = false;
  double number_ = 0.0;
  std::string string_;
  std::vector<std::string> keys_;  // object member names
  std::vector<Json> items_;        // array elements or object member values
};

const char* json_type_name(Json::Type type);

// Parses one JSON text (surrounding whitespace allowed). Malformed input throws
// mcon::Error(MCON_ERROR_INVALID_ARGUMENT, "JSON: <what> at offset <n> (line <l>, column <c>)").
Json parse_json(std::string_view text);

// Pretty output indents by two spaces and keeps arrays of plain values on one line; compact output
// has no whitespace at all. Non-finite numbers throw mcon::Error(MCON_ERROR_NON_FINITE), strings
// that are not UTF-8 mcon::Error(MCON_ERROR_INVALID_ARGUMENT).
std::string write_json(const Json& value, bool pretty = true);

}  // namespace mcon::tools
