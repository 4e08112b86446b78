#include "json/json.h"

#include <charconv>
#include <cmath>
#include <cstdint>

#include "base/error.h"  // header-only: mcon::Error, fail, require (no link dependency on the core)

namespace mcon::tools {

namespace {

constexpr double kMaxExactInteger = 9007199254740992.0;  // 2^53
constexpr int kMaxDepth = 512;                           // nesting limit: no stack exhaustion

[[noreturn]] void type_error(const std::string& message) { fail(MCON_ERROR_INVALID_ARGUMENT, "JSON: " + message); }

// Length of the UTF-8 sequence starting at s[i], or 0 if it is not a valid (shortest-form,
// non-surrogate, <= U+10FFFF) sequence.
std::size_t utf8_sequence_length(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  const unsigned char c = byte(i);
  if (c < 0x80) return 1;
  std::size_t n = 0;
  std::uint32_t code = 0;
  if (c >= 0xC2 && c <= 0xDF) {
    n = 2;
    code = c & 0x1F;
  } else if (c >= 0xE0 && c <= 0xEF) {
    n = 3;
    code = c & 0x0F;
  } else if (c >= 0xF0 && c <= 0xF4) {
    n = 4;
    code = c & 0x07;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (std::size_t k = 1; k < n; ++k) {
    if ((byte(i + k) & 0xC0) != 0x80) return 0;
    code = (code << 6) | (byte(i + k) & 0x3F);
  }
  if ((n == 3 && code < 0x800) || (n == 4 && code < 0x10000) || code > 0x10FFFF) return 0;
  if (code >= 0xD800 && code <= 0xDFFF) return 0;
  return n;
}

void append_utf8(std::string& out, std::uint32_t code) {
  if (code < 0x80) {
    out += static_cast<char>(code);
  } else if (code < 0x800) {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

class Parser {
 public:
  explicit Parser(std::string_view text) : s_(text) {}

  Json parse_document() {
    skip_whitespace();
    Json value = parse_value(0);
    skip_whitespace();
    if (pos_ != s_.size()) error("unexpected text after the value");
    return value;
  }

 private:
  [[noreturn]] void error(const std::string& what) const { error_at(what, pos_); }

  [[noreturn]] void error_at(const std::string& what, std::size_t offset) const {
    std::size_t line = 1, column = 1;
    for (std::size_t i = 0; i < offset && i < s_.size(); ++i) {
      if (s_[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    fail(MCON_ERROR_INVALID_ARGUMENT, "JSON: " + what + " at offset " + std::to_string(offset) + " (line " +
                                          std::to_string(line) + ", column " + std::to_string(column) + ")");
  }

  bool at_end() const { return pos_ >= s_.size(); }
  char peek() const { return at_end() ? '\0' : s_[pos_]; }

  void skip_whitespace() {
    while (!at_end() && (s_[pos_] == ' ' || s_[pos_] == '\t' || s_[pos_] == '\n' || s_[pos_] == '\r')) ++pos_;
  }

  void expect_literal(std::string_view word) {
    if (s_.substr(pos_, word.size()) != word) error("invalid literal (expected '" + std::string(word) + "')");
    pos_ += word.size();
  }

  Json parse_value(int depth) {
    if (at_end()) error("unexpected end of input (expected a value)");
    switch (peek()) {
      case '{':
        return parse_object(depth + 1);
      case '[':
        return parse_array(depth + 1);
      case '"':
        return Json(parse_string());
      case 't':
        expect_literal("true");
        return Json(true);
      case 'f':
        expect_literal("false");
        return Json(false);
      case 'n':
        expect_literal("null");
        return Json();
      default:
        if (peek() == '-' || (peek() >= '0' && peek() <= '9')) return Json(parse_number());
        error(std::string("unexpected character '") + peek() + "'");
    }
  }

  void check_depth(int depth) const {
    if (depth > kMaxDepth) error("nesting deeper than " + std::to_string(kMaxDepth));
  }

  Json parse_object(int depth) {
    check_depth(depth);
    ++pos_;  // '{'
    Json object = Json::object();
    skip_whitespace();
    if (peek() == '}') {
      ++pos_;
      return object;
    }
    for (;;) {
      skip_whitespace();
      if (peek() != '"') error("expected a member name in double quotes");
      const std::size_t key_offset = pos_;
      std::string key = parse_string();
      if (object.contains(key)) error_at("duplicate member name \"" + key + "\"", key_offset);
      skip_whitespace();
      if (peek() != ':') error("expected ':' after a member name");
      ++pos_;
      skip_whitespace();
      object.set(std::move(key), parse_value(depth));
      skip_whitespace();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() == '}') {
        ++pos_;
        return object;
      }
      error(at_end() ? "unexpected end of input in an object" : "expected ',' or '}' in an object");
    }
  }

  Json parse_array(int depth) {
    check_depth(depth);
    ++pos_;  // '['
    Json array = Json::array();
    skip_whitespace();
    if (peek() == ']') {
      ++pos_;
      return array;
    }
    for (;;) {
      skip_whitespace();
      array.push_back(parse_value(depth));
      skip_whitespace();
      if (peek() == ',') {
        ++pos_;
        continue;
      }
      if (peek() == ']') {
        ++pos_;
        return array;
      }
      error(at_end() ? "unexpected end of input in an array" : "expected ',' or ']' in an array");
    }
  }

  std::uint32_t parse_hex4() {
    if (pos_ + 4 > s_.size()) error("truncated \\u escape");
    std::uint32_t code = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = s_[pos_ + k];
      code <<= 4;
      if (c >= '0' && c <= '9') code |= static_cast<std::uint32_t>(c - '0');
      else if (c >= 'a' && c <= 'f') code |= static_cast<std::uint32_t>(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') code |= static_cast<std::uint32_t>(c - 'A' + 10);
      else error_at("invalid hex digit in \\u escape", pos_ + k);
    }
    pos_ += 4;
    return code;
  }

  std::string parse_string() {
    const std::size_t start = pos_;
    ++pos_;  // opening quote
    std::string out;
    for (;;) {
      if (at_end()) error_at("unterminated string", start);
      const char c = s_[pos_];
      if (c == '"') {
        ++pos_;
        return out;
      }
      if (static_cast<unsigned char>(c) < 0x20) error("unescaped control character in a string");
      if (c != '\\') {
        const std::size_t n = utf8_sequence_length(s_, pos_);
        if (n == 0) error("invalid UTF-8 in a string");
        out.append(s_.substr(pos_, n));
        pos_ += n;
        continue;
      }
      const std::size_t escape_offset = pos_;
      ++pos_;
      if (at_end()) error_at("unterminated string", start);
      const char e = s_[pos_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t code = parse_hex4();
          if (code >= 0xDC00 && code <= 0xDFFF) error_at("lone low surrogate in \\u escape", escape_offset);
          if (code >= 0xD800 && code <= 0xDBFF) {
            if (s_.substr(pos_, 2) != "\\u") error_at("high surrogate without a low surrogate", escape_offset);
            pos_ += 2;
            const std::uint32_t low = parse_hex4();
            if (low < 0xDC00 || low > 0xDFFF) error_at("high surrogate without a low surrogate", escape_offset);
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          append_utf8(out, code);
          break;
        }
        default:
          error_at(std::string("invalid escape '\\") + e + "'", escape_offset);
      }
    }
  }

  double parse_number() {
    const std::size_t start = pos_;
    const auto digit = [&] { return !at_end() && s_[pos_] >= '0' && s_[pos_] <= '9'; };
    if (peek() == '-') ++pos_;
    if (!digit()) error("expected a digit");
    if (s_[pos_] == '0') {
      ++pos_;
      if (digit()) error_at("leading zero in a number", start);
    } else {
      while (digit()) ++pos_;
    }
    if (peek() == '.') {
      ++pos_;
      if (!digit()) error("expected a digit after the decimal point");
      while (digit()) ++pos_;
    }
    if (peek() == 'e' || peek() == 'E') {
      ++pos_;
      if (peek() == '+' || peek() == '-') ++pos_;
      if (!digit()) error("expected a digit in the exponent");
      while (digit()) ++pos_;
    }
    double value = 0.0;
    const char* first = s_.data() + start;
    const char* last = s_.data() + pos_;
    const auto result = std::from_chars(first, last, value);
    if (result.ec == std::errc::result_out_of_range) {
      // Underflow to zero is harmless; overflow is not representable.
      bool nonzero_digit = false;
      bool in_exponent = false;
      bool negative_exponent = false;
      for (const char* p = first; p != last; ++p) {
        if (*p == 'e' || *p == 'E') in_exponent = true;
        else if (in_exponent && *p == '-') negative_exponent = true;
        else if (!in_exponent && *p >= '1' && *p <= '9') nonzero_digit = true;
      }
      if (nonzero_digit && !negative_exponent) error_at("number out of range", start);
      return *first == '-' ? -0.0 : 0.0;
    }
    if (result.ec != std::errc() || result.ptr != last) error_at("invalid number", start);
    return value;
  }

  std::string_view s_;
  std::size_t pos_ = 0;
};

void write_string(std::string& out, const std::string& s) {
  out += '"';
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    switch (c) {
      case '"': out += "\\\""; ++i; continue;
      case '\\': out += "\\\\"; ++i; continue;
      case '\b': out += "\\b"; ++i; continue;
      case '\f': out += "\\f"; ++i; continue;
      case '\n': out += "\\n"; ++i; continue;
      case '\r': out += "\\r"; ++i; continue;
      case '\t': out += "\\t"; ++i; continue;
      default: break;
    }
    if (c < 0x20) {
      static const char hex[] = "0123456789abcdef";
      out += "\\u00";
      out += hex[c >> 4];
      out += hex[c & 15];
      ++i;
      continue;
    }
    const std::size_t n = utf8_sequence_length(s, i);
    if (n == 0) type_error("cannot write a string that is not valid UTF-8 (byte " + std::to_string(i) + ")");
    out.append(s, i, n);
    i += n;
  }
  out += '"';
}

void write_number(std::string& out, double value) {
  if (!std::isfinite(value)) fail(MCON_ERROR_NON_FINITE, "JSON: cannot write a non-finite number");
  char buffer[64];
  // Shortest representation that reads back to the same double.
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  out.append(buffer, result.ptr);
}

bool is_container(const Json& v) { return v.is_array() || v.is_object(); }

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

Json parse_json(std::string_view text) { return Parser(text).parse_document(); }

std::string write_json(const Json& value, bool pretty) {
  std::string out;
  write_value(out, value, pretty, 0);
  if (pretty) out += '\n';
  return out;
}

}  // namespace mcon::tools
