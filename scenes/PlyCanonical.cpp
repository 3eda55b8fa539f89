#include "scenes/PlyCanonical.h"

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <vector>

#include "core/Errors.h"

namespace cdb {
namespace {

enum class Format { Ascii, LittleEndian, BigEndian };

struct ScalarType {
  std::string_view name;  // as written out
  int size = 0;           // bytes in a binary body
  bool isSigned = false;
  bool isInteger = false;
};

constexpr ScalarType kTypes[] = {{"char", 1, true, true},   {"uchar", 1, false, true},
                                 {"short", 2, true, true},  {"ushort", 2, false, true},
                                 {"int", 4, true, true},    {"uint", 4, false, true},
                                 {"float", 4, true, false}, {"double", 8, true, false}};
// The sized names the format also allows, in the order of kTypes.
constexpr std::string_view kSizedNames[] = {"int8",  "uint8",  "int16",   "uint16",
                                            "int32", "uint32", "float32", "float64"};

std::optional<ScalarType> typeNamed(std::string_view word) {
  for (std::size_t k = 0; k < std::size(kTypes); ++k)
    if (word == kTypes[k].name || word == kSizedNames[k]) return kTypes[k];
  return std::nullopt;
}

// The elements assimp reads. It gives any other element no items.
constexpr std::string_view kKnownElements[] = {"vertex", "face", "tristrips", "edge", "material"};

bool isKnown(std::string_view element) {
  return std::find(std::begin(kKnownElements), std::end(kKnownElements), element) !=
         std::end(kKnownElements);
}

struct Property {
  std::string name;
  ScalarType type;                   // a scalar's, or each list item's
  std::optional<ScalarType> length;  // a list's length; none for a scalar
};

struct Element {
  std::string name;
  std::uint32_t count = 0;
  std::vector<Property> properties;
  int line = 0;  // in the header
};

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
};

// Header text in a message: control bytes as \xHH, long text cut.
std::string shown(std::string_view text) {
  constexpr std::size_t kMost = 60;
  std::string out;
  for (const char c : text.substr(0, kMost)) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      constexpr char kHex[] = "0123456789ABCDEF";
      out += "\\x";
      out += kHex[byte >> 4];
      out += kHex[byte & 0xf];
    } else {
      out += c;
    }
  }
  if (text.size() > kMost) out += "...";
  return out;
}

std::vector<std::string_view> wordsOf(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t at = 0;
  while (true) {
    at = line.find_first_not_of(" \t", at);
    if (at == std::string_view::npos) return words;
    const std::size_t end = std::min(line.find_first_of(" \t", at), line.size());
    words.push_back(line.substr(at, end - at));
    at = end;
  }
}

std::optional<std::uint32_t> countOf(std::string_view word) {
  std::uint32_t value = 0;
  if (word.empty() || word.front() < '0' || word.front() > '9') return std::nullopt;
  const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (ec != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

class HeaderReader {
 public:
  explicit HeaderReader(const std::string& name) : name_(name) {}

  Header read(std::string_view header) {
    std::size_t at = 0;
    while (at < header.size()) {
      const std::size_t end = std::min(header.find('\n', at), header.size());
      std::string_view line = header.substr(at, end - at);
      at = end + 1;
      ++line_;
      while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      if (readLine(line)) break;
    }
    if (!formatSeen_) {
      throw InputError(name_ +
                       ": PLY header: expected a line 'format ascii 1.0' (or binary_little_endian, "
                       "binary_big_endian), got none");
    }
    return header_;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError(name_ + ": PLY header line " + std::to_string(line_) + ": " + what);
  }

  // True on the line that ends the header.
  bool readLine(std::string_view line) {
    const auto words = wordsOf(line);
    if (line_ == 1) {
      if (words.size() != 1 || (words[0] != "ply" && words[0] != "PLY"))
        fail("expected the line 'ply', got '" + shown(line) + "'");
      return false;
    }
    if (words.empty()) return false;
    if (words[0] == "comment" || words[0] == "obj_info") return false;  // not written out
    for (const char c : line) {
      const auto byte = static_cast<unsigned char>(c);
      if ((byte < 0x20 && c != '\t') || byte == 0x7f)
        fail("expected printable text, got '" + shown(line) + "'");
    }
    if (words[0] == "end_header") return true;
    if (words[0] == "format") {
      readFormat(words);
    } else if (words[0] == "element") {
      readElement(words, line);
    } else if (words[0] == "property") {
      readProperty(words, line);
    } else {
      fail("expected format, element, property, comment or obj_info, got '" + shown(words[0]) +
           "'");
    }
    return false;
  }

  void readFormat(const std::vector<std::string_view>& words) {
    if (formatSeen_) fail("expected one format line, got a second");
    if (!header_.elements.empty()) fail("expected the format line before the elements");
    const std::string_view f = words.size() >= 2 ? words[1] : "";
    if (f == "ascii")
      header_.format = Format::Ascii;
    else if (f == "binary_little_endian")
      header_.format = Format::LittleEndian;
    else if (f == "binary_big_endian")
      header_.format = Format::BigEndian;
    else
      fail("expected format ascii, binary_little_endian or binary_big_endian, got '" + shown(f) +
           "'");
    formatSeen_ = true;
  }

  void readElement(const std::vector<std::string_view>& words, std::string_view line) {
    if (words.size() != 3) fail("expected 'element NAME COUNT', got '" + shown(line) + "'");
    Element e;
    e.name = std::string(words[1]);
    e.line = line_;
    const auto count = countOf(words[2]);
    if (!count)
      fail("expected a count of element '" + shown(e.name) + "' from 0 to 4294967295, got '" +
           shown(words[2]) + "'");
    e.count = *count;
    for (const Element& before : header_.elements)
      if (before.name == e.name) fail("element '" + shown(e.name) + "' is declared twice");
    header_.elements.push_back(std::move(e));
  }

  ScalarType typeOf(std::string_view word) const {
    const auto type = typeNamed(word);
    if (!type)
      fail(
          "expected a PLY type (char, uchar, short, ushort, int, uint, float, double, or int8 to "
          "float64), got '" +
          shown(word) + "'");
    return *type;
  }

  void readProperty(const std::vector<std::string_view>& words, std::string_view line) {
    if (header_.elements.empty()) fail("expected an element line before a property");
    Property p;
    if (words.size() >= 2 && words[1] == "list") {
      if (words.size() != 5)
        fail("expected 'property list LENGTH_TYPE ITEM_TYPE NAME', got '" + shown(line) + "'");
      p.length = typeOf(words[2]);
      if (!p.length->isInteger)
        fail("expected an integer type for a list's length, got '" + shown(words[2]) + "'");
      p.type = typeOf(words[3]);
      p.name = std::string(words[4]);
    } else {
      if (words.size() != 3) fail("expected 'property TYPE NAME', got '" + shown(line) + "'");
      p.type = typeOf(words[1]);
      p.name = std::string(words[2]);
    }
    header_.elements.back().properties.push_back(std::move(p));
  }

  const std::string& name_;
  Header header_;
  bool formatSeen_ = false;
  int line_ = 0;
};

// The elements written out: those assimp reads. An element it does not know is dropped; one with
// items is refused when a known element follows, whose data assimp would then read from the
// wrong place. A known element with items but no properties is refused: assimp would allocate
// its items without reading anything.
std::vector<Element> elementsForAssimp(const Header& h, const std::string& name) {
  std::vector<Element> kept;
  for (std::size_t i = 0; i < h.elements.size(); ++i) {
    const Element& e = h.elements[i];
    const auto fail = [&](const std::string& what) {
      throw InputError(name + ": PLY header line " + std::to_string(e.line) + ": element '" +
                       shown(e.name) + "' " + what);
    };
    if (isKnown(e.name)) {
      if (e.count > 0 && e.properties.empty())
        fail("has " + std::to_string(e.count) + " items but no properties");
      kept.push_back(e);
      continue;
    }
    if (e.count == 0) continue;
    for (std::size_t j = i + 1; j < h.elements.size(); ++j)
      if (isKnown(h.elements[j].name))
        fail("(" + std::to_string(e.count) + " items) comes before element '" + h.elements[j].name +
             "': the mesh reader reads only vertex, face, tristrips, edge and material elements, "
             "and would read the data after this one from the wrong place");
  }
  return kept;
}

std::string headerText(Format format, const std::vector<Element>& elements) {
  std::string out = "ply\nformat ";
  out += format == Format::Ascii          ? "ascii"
         : format == Format::LittleEndian ? "binary_little_endian"
                                          : "binary_big_endian";
  out += " 1.0\n";
  for (const Element& e : elements) {
    out += "element " + e.name + " " + std::to_string(e.count) + "\n";
    for (const Property& p : e.properties) {
      out += "property ";
      if (p.length) out += "list " + std::string(p.length->name) + " ";
      out += std::string(p.type.name) + " " + p.name + "\n";
    }
  }
  return out + "end_header\n";
}

[[noreturn]] void failElement(const std::string& name, const Element& e, std::uint64_t item,
                              const std::string& why) {
  throw InputError(name + ": PLY element '" + e.name + "' " + std::to_string(item) + " of " +
                   std::to_string(e.count) + ": " + why + " (the file is cut short or a count " +
                   "in it is corrupt)");
}

void checkBinary(std::string_view body, Format format, const std::vector<Element>& elements,
                 const std::string& name) {
  std::size_t at = 0;
  // A list's length; -1 for a negative one.
  const auto readLength = [&](const ScalarType& type) -> long double {
    std::uint64_t v = 0;
    for (int k = 0; k < type.size; ++k) {
      const int shift = format == Format::LittleEndian ? 8 * k : 8 * (type.size - 1 - k);
      v |= std::uint64_t(static_cast<unsigned char>(body[at + std::size_t(k)])) << shift;
    }
    at += std::size_t(type.size);
    if (type.isSigned && (v >> (8 * type.size - 1)) & 1) return -1;
    return static_cast<long double>(v);
  };
  for (const Element& e : elements) {
    bool hasList = false;
    std::uint64_t fixed = 0;
    for (const Property& p : e.properties) {
      hasList = hasList || p.length.has_value();
      fixed += std::uint64_t(p.type.size);
    }
    if (!hasList) {
      const long double need = static_cast<long double>(e.count) * fixed;
      if (need > static_cast<long double>(body.size() - at))
        failElement(name, e, (body.size() - at) / (fixed ? fixed : 1),
                    "expected " + std::to_string(e.count) + " items of " + std::to_string(fixed) +
                        " bytes, the file has " + std::to_string(body.size() - at) + " bytes left");
      at += std::size_t(need);
      continue;
    }
    // Each item reads at least one length, so this loop is bounded by the file's size.
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const Property& p : e.properties) {
        const std::size_t left = body.size() - at;
        if (!p.length) {
          if (std::size_t(p.type.size) > left) failElement(name, e, i, "the data ends inside it");
          at += std::size_t(p.type.size);
          continue;
        }
        if (std::size_t(p.length->size) > left) failElement(name, e, i, "the data ends inside it");
        const long double n = readLength(*p.length);
        if (n < 0) failElement(name, e, i, "expected a list length >= 0, got a negative one");
        const long double bytes = n * p.type.size;
        if (bytes > static_cast<long double>(body.size() - at))
          failElement(name, e, i,
                      "a list of " + std::to_string(std::uint64_t(n)) +
                          " items does not fit in the " + std::to_string(body.size() - at) +
                          " bytes left");
        at += std::size_t(bytes);
      }
    }
  }
}

// An ASCII value as assimp will read it: an integer type's value written out plainly (assimp's
// unsigned reader stops at a sign), a real number's token as it is once it is known to be one.
std::optional<std::string> valueText(std::string_view token, const ScalarType& type) {
  const std::string_view digits = token.starts_with('+') ? token.substr(1) : token;
  if (digits.empty() || (digits.size() < token.size() && (digits[0] == '+' || digits[0] == '-')))
    return std::nullopt;
  if (type.isInteger) {
    std::int64_t v = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
    if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
    if (v < 0 && !type.isSigned) return std::nullopt;
    return std::to_string(v);
  }
  if (digits.find('(') != std::string_view::npos) return std::nullopt;  // nan(...)
  double v = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (ec != std::errc() || end != digits.data() + digits.size()) return std::nullopt;
  return std::string(token);
}

class AsciiTokens {
 public:
  explicit AsciiTokens(std::string_view body) : body_(body) {}
  std::optional<std::string_view> next() {
    while (at_ < body_.size() && isSpace(body_[at_])) ++at_;
    if (at_ == body_.size()) return std::nullopt;
    const std::size_t start = at_;
    while (at_ < body_.size() && !isSpace(body_[at_])) ++at_;
    return body_.substr(start, at_ - start);
  }
  [[nodiscard]] std::size_t bytesLeft() const { return body_.size() - at_; }

 private:
  static bool isSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
  }
  std::string_view body_;
  std::size_t at_ = 0;
};

// One item per line, its values as valueText writes them.
std::string asciiBody(std::string_view body, const std::vector<Element>& elements,
                      const std::string& name) {
  AsciiTokens tokens(body);
  std::string out;
  out.reserve(body.size() + 1);
  for (const Element& e : elements) {
    // Each item reads at least one token, so this loop is bounded by the file's size.
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const std::size_t lineStart = out.size();
      const auto put = [&](const Property& p, std::string_view token, const ScalarType& type) {
        const auto text = valueText(token, type);
        if (!text)
          failElement(name, e, i,
                      "expected " + std::string(type.isInteger ? "an integer" : "a number") +
                          (type.isInteger && !type.isSigned ? " >= 0" : "") + " (" +
                          std::string(type.name) + ") for property '" + p.name + "', got '" +
                          shown(token) + "'");
        if (out.size() > lineStart) out += ' ';
        out += *text;
      };
      for (const Property& p : e.properties) {
        const auto token = tokens.next();
        if (!token) failElement(name, e, i, "the data ends before it");
        if (!p.length) {
          put(p, *token, p.type);
          continue;
        }
        if (token->starts_with('-'))
          failElement(name, e, i, "expected a list length >= 0, got '" + shown(*token) + "'");
        const auto n = countOf(token->starts_with('+') ? token->substr(1) : *token);
        if (!n)
          failElement(name, e, i,
                      "expected a list length from 0 to 4294967295, got '" + shown(*token) + "'");
        // At least two bytes (a digit and a separator) per remaining item, but the last.
        if (*n > tokens.bytesLeft() / 2 + 1)
          failElement(name, e, i,
                      "a list of " + std::to_string(*n) + " items does not fit in the " +
                          std::to_string(tokens.bytesLeft()) + " bytes left");
        if (out.size() > lineStart) out += ' ';
        out += std::to_string(*n);
        for (std::uint32_t k = 0; k < *n; ++k) {
          const auto item = tokens.next();
          if (!item) failElement(name, e, i, "the data ends inside its list");
          put(p, *item, p.type);
        }
      }
      out += '\n';
    }
  }
  return out;
}

}  // namespace

std::string canonicalPly(std::string_view text, std::size_t bodyStart, const std::string& name) {
  bodyStart = std::min(bodyStart, text.size());
  const Header header = HeaderReader(name).read(text.substr(0, bodyStart));
  const std::vector<Element> elements = elementsForAssimp(header, name);
  const std::string_view body = text.substr(bodyStart);
  if (header.format == Format::Ascii)
    return headerText(header.format, elements) + asciiBody(body, elements, name);
  checkBinary(body, header.format, elements, name);
  std::string out = headerText(header.format, elements);
  out += body;
  return out;
}

}  // namespace cdb
