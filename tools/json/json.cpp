#include "json/json.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>

#include <nlohmann/json.hpp>

#include "base/error.h"  // header-only: mcon::Error, fail, require (no link dependency on the core)

namespace mcon::tools {

namespace {

constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53
constexpr int kMaxDepth = 512;                           // nesting limit for the documents we build

[[noreturn]] void type_error(const std::string& message) { fail(MCON_ERROR_INVALID_ARGUMENT, "JSON: " + message); }

[[noreturn]] void error_at(std::string_view text, const std::string& what, std::size_t offset) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  fail(MCON_ERROR_INVALID_ARGUMENT, "JSON: " + what + " at offset " + std::to_string(offset) + " (line " +
                                        std::to_string(line) + ", column " + std::to_string(column) + ")");
}

// A char iterator that publishes how far nlohmann's lexer has read, so the handler below can name
// the offset of the errors it finds itself (duplicate names, nesting, overflow).
class ReadCursor {
 public:
  using iterator_category = std::forward_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  ReadCursor(const char* p, const char** read) : p_(p), read_(read) {}
  reference operator*() const { return *p_; }
  ReadCursor& operator++() {
    *read_ = ++p_;
    return *this;
  }
  ReadCursor operator++(int) {
    ReadCursor before = *this;
    ++*this;
    return before;
  }
  bool operator==(const ReadCursor& other) const { return p_ == other.p_; }
  bool operator!=(const ReadCursor& other) const { return p_ != other.p_; }

 private:
  const char* p_;
  const char** read_;
};

// nlohmann's SAX events, built into a Json. nlohmann tokenizes and enforces RFC 8259 (no comments,
// trailing commas, leading zeros, unescaped control characters, invalid UTF-8 or lone surrogates);
// this handler adds what it allows: duplicate member names, numbers that overflow a double (nlohmann
// reports those as an error too, without the offset) and unbounded nesting.
class JsonBuilder : public nlohmann::json_sax<nlohmann::json> {
 public:
  JsonBuilder(std::string_view text, const char* const* read) : text_(text), read_(read) {}

  bool null() override { return add(Json()); }
  bool boolean(bool value) override { return add(Json(value)); }
  bool number_integer(number_integer_t value) override { return add(Json(static_cast<double>(value))); }
  bool number_unsigned(number_unsigned_t value) override { return add(Json(static_cast<double>(value))); }
  bool number_float(number_float_t value, const string_t&) override { return add(Json(value)); }
  bool string(string_t& value) override { return add(Json(std::move(value))); }
  bool binary(binary_t&) override { return stop("binary values are not JSON", read_offset()); }
  bool start_object(std::size_t) override { return open(Json::object()); }
  bool start_array(std::size_t) override { return open(Json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& name) override {
    // The lexer has just read the name's closing quote; its opening quote is the last one before
    // it that no backslash escapes (a quote inside a JSON string is always escaped).
    if (stack_.back()->contains(name)) return stop("duplicate member name \"" + name + "\"", opening_quote());
    key_ = std::move(name);
    return true;
  }
  bool parse_error(std::size_t position, const std::string& last_token, const nlohmann::detail::exception& e) override {
    std::string what = e.what();
    const std::size_t colon = what.find(": ");
    if (what.find("parse error") != std::string::npos && colon != std::string::npos) what = what.substr(colon + 2);
    // The offset says where; nlohmann's "last read: '...'" would echo raw (possibly invalid) bytes.
    const std::size_t echo = what.find("; last read: '");
    if (echo != std::string::npos) {
      const std::size_t echo_end = what.find("'", echo + 14);
      what.erase(echo, echo_end == std::string::npos ? std::string::npos : echo_end + 1 - echo);
    }
    // nlohmann's position counts the bytes read, the offending one included.
    std::size_t offset = position > 0 ? position - 1 : 0;
    if (e.id == 406) {  // a number too large for a double: name where it starts
      what = "number out of range";
      offset = position >= last_token.size() ? position - last_token.size() : 0;
    }
    return stop(what, std::min(offset, text_.size()));
  }

  Json take() {
    if (!message_.empty()) error_at(text_, message_, offset_);
    return std::move(root_);
  }

 private:
  std::size_t read_offset() const { return static_cast<std::size_t>(*read_ - text_.data()); }

  std::size_t opening_quote() const {
    std::size_t q = read_offset() >= 2 ? read_offset() - 2 : 0;
    while (q > 0) {
      if (text_[q] == '"') {
        std::size_t backslashes = 0;
        while (q > backslashes && text_[q - 1 - backslashes] == '\\') ++backslashes;
        if (backslashes % 2 == 0) break;
      }
      --q;
    }
    return q;
  }

  bool stop(std::string what, std::size_t offset) {
    if (message_.empty()) {
      message_ = std::move(what);
      offset_ = offset;
    }
    return false;
  }

  Json* place(Json value) {
    if (stack_.empty()) {
      root_ = std::move(value);
      return &root_;
    }
    Json& parent = *stack_.back();
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent[parent.size() - 1];
    }
    return &parent.set(std::move(key_), std::move(value));
  }

  bool add(Json value) {
    place(std::move(value));
    return true;
  }

  bool open(Json container) {
    if (static_cast<int>(stack_.size()) >= kMaxDepth)
      return stop("nesting deeper than " + std::to_string(kMaxDepth), read_offset() - 1);
    stack_.push_back(place(std::move(container)));
    return true;
  }

  bool close() {
    stack_.pop_back();
    return true;
  }

  std::string_view text_;
  const char* const* read_;
  Json root_;
  std::vector<Json*> stack_;  // open containers; a parent never moves while a child is open
  std::string key_;
  std::string message_;
  std::size_t offset_ = 0;
};

// Scalars are written by nlohmann's serializer: strings UTF-8-checked and escaped, doubles in the
// shortest form that reads back to the same bits. Integral values within 2^53 are written as
// integers ("3", not "3.0"), as a reader expects counts to look.
void write_string(std::string& out, const std::string& s) {
  try {
    out += nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::strict);
  } catch (const nlohmann::json::type_error& e) {
    type_error(std::string("cannot write a string that is not valid UTF-8 (") + e.what() + ")");
  }
}

void write_number(std::string& out, double value) {
  if (!std::isfinite(value)) fail(MCON_ERROR_NON_FINITE, "JSON: cannot write a non-finite number");
  if (value == std::floor(value) && std::fabs(value) <= kMaxExactInteger && !std::signbit(value))
    out += nlohmann::json(static_cast<std::uint64_t>(value)).dump();
  else if (value == std::floor(value) && std::fabs(value) <= kMaxExactInteger && value != 0.0)
    out += nlohmann::json(static_cast<std::int64_t>(value)).dump();
  else
    out += nlohmann::json(value).dump();
}

bool is_container(const Json& v) { return v.is_array() || v.is_object(); }

// The layout is ours: nlohmann's pretty printer puts every array element on its own line, which
// makes per-class and per-case number lists unreadable; here arrays of plain values stay on one.
void write_value(std::string& out, const Json& v, bool pretty, int indent) {
  const auto newline = [&](int level) {
    out += '\n';
    out.append(static_cast<std::size_t>(2 * level), ' ');
  };
  switch (v.type()) {
    case Json::Type::Null: out += "null"; return;
    case Json::Type::Bool: out += v.as_bool() ? "true" : "false"; return;
    case Json::Type::Number: write_number(out, v.as_number()); return;
    case Json::Type::String: write_string(out, v.as_string()); return;
    case Json::Type::Array: {
      if (v.size() == 0) {
        out += "[]";
        return;
      }
      bool flat = true;  // arrays of plain values stay on one line
      for (const Json& e : v.elements()) flat = flat && !is_container(e);
      out += '[';
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (i > 0) out += pretty && flat ? ", " : ",";
        if (pretty && !flat) newline(indent + 1);
        write_value(out, v[i], pretty, indent + 1);
      }
      if (pretty && !flat) newline(indent);
      out += ']';
      return;
    }
    case Json::Type::Object: {
      if (v.size() == 0) {
        out += "{}";
        return;
      }
      out += '{';
      for (std::size_t i = 0; i < v.size(); ++i) {
        if (i > 0) out += ',';
        if (pretty) newline(indent + 1);
        write_string(out, v.key(i));
        out += pretty ? ": " : ":";
        write_value(out, v.value(i), pretty, indent + 1);
      }
      if (pretty) newline(indent);
      out += '}';
      return;
    }
  }
}

}  // namespace

const char* json_type_name(Json::Type type) {
  switch (type) {
    case Json::Type::Null: return "null";
    case Json::Type::Bool: return "boolean";
    case Json::Type::Number: return "number";
    case Json::Type::String: return "string";
    case Json::Type::Array: return "array";
    case Json::Type::Object: return "object";
  }
  return "?";
}

void Json::expect(Type type, const char* what) const {
  if (type_ != type)
    type_error(std::string(what) + " needs " + json_type_name(type) + ", the value is " + json_type_name(type_));
}

bool Json::as_bool() const {
  expect(Type::Bool, "as_bool");
  return bool_;
}

double Json::as_number() const {
  expect(Type::Number, "as_number");
  return number_;
}

long long Json::as_int() const {
  expect(Type::Number, "as_int");
  if (number_ != std::floor(number_) || std::fabs(number_) > kMaxExactInteger)
    type_error("as_int needs an integer within +-2^53, the value is " + write_json(*this, false));
  return static_cast<long long>(number_);
}

const std::string& Json::as_string() const {
  expect(Type::String, "as_string");
  return string_;
}

std::size_t Json::size() const {
  if (type_ != Type::Array && type_ != Type::Object)
    type_error(std::string("size needs an array or object, the value is ") + json_type_name(type_));
  return items_.size();
}

const Json& Json::operator[](std::size_t index) const {
  expect(Type::Array, "operator[]");
  if (index >= items_.size())
    type_error("index " + std::to_string(index) + " out of range (array of " + std::to_string(items_.size()) + ")");
  return items_[index];
}

Json& Json::operator[](std::size_t index) {
  return const_cast<Json&>(static_cast<const Json&>(*this)[index]);
}

const std::vector<Json>& Json::elements() const {
  expect(Type::Array, "elements");
  return items_;
}

void Json::push_back(Json value) {
  expect(Type::Array, "push_back");
  items_.push_back(std::move(value));
}

const std::string& Json::key(std::size_t index) const {
  expect(Type::Object, "key");
  if (index >= keys_.size()) type_error("member index " + std::to_string(index) + " out of range");
  return keys_[index];
}

const Json& Json::value(std::size_t index) const {
  expect(Type::Object, "value");
  if (index >= items_.size()) type_error("member index " + std::to_string(index) + " out of range");
  return items_[index];
}

const Json* Json::find(std::string_view key) const {
  expect(Type::Object, "find");
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return &items_[i];
  return nullptr;
}

const Json& Json::at(std::string_view key) const {
  const Json* member = find(key);
  if (member == nullptr) fail(MCON_ERROR_NOT_FOUND, "JSON: no member \"" + std::string(key) + "\"");
  return *member;
}

Json& Json::set(std::string key, Json value) {
  expect(Type::Object, "set");
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return items_[i] = std::move(value);
  keys_.push_back(std::move(key));
  items_.push_back(std::move(value));
  return items_.back();
}

bool Json::operator==(const Json& other) const {
  if (type_ != other.type_) return false;
  switch (type_) {
    case Type::Null: return true;
    case Type::Bool: return bool_ == other.bool_;
    case Type::Number: return number_ == other.number_;
    case Type::String: return string_ == other.string_;
    case Type::Array: return items_ == other.items_;
    case Type::Object: return keys_ == other.keys_ && items_ == other.items_;
  }
  return false;
}

Json parse_json(std::string_view text) {
  const char* read = text.data();
  JsonBuilder builder(text, &read);
  const ReadCursor first(text.data(), &read), last(text.data() + text.size(), &read);
  nlohmann::json::sax_parse(first, last, &builder, nlohmann::json::input_format_t::json, /*strict=*/true,
                            /*ignore_comments=*/false);
  return builder.take();
}

std::string write_json(const Json& value, bool pretty) {
  std::string out;
  write_value(out, value, pretty, 0);
  if (pretty) out += '\n';
  return out;
}

}  // namespace mcon::tools
