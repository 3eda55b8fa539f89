#include "scenes/PlyBounds.h"

#include <cctype>
#include <charconv>
#include <cstdint>
#include <optional>
#include <sstream>
#include <vector>

#include "core/Errors.h"

namespace cdb {
namespace {

struct Property {
  int size = 0;       // bytes of a scalar, or of each list item
  int countSize = 0;  // bytes of a list's count; 0 for a scalar
  bool countSigned = false;
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Format { Ascii, LittleEndian, BigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
};

std::optional<std::pair<int, bool>> typeSize(std::string_view t) {
  if (t == "char" || t == "int8") return std::pair{1, true};
  if (t == "uchar" || t == "uint8") return std::pair{1, false};
  if (t == "short" || t == "int16") return std::pair{2, true};
  if (t == "ushort" || t == "uint16") return std::pair{2, false};
  if (t == "int" || t == "int32") return std::pair{4, true};
  if (t == "uint" || t == "uint32") return std::pair{4, false};
  if (t == "float" || t == "float32") return std::pair{4, true};
  if (t == "double" || t == "float64") return std::pair{8, true};
  return std::nullopt;
}

// nullopt: a header this check does not follow; assimp has the last word on it.
std::optional<Header> parseHeader(std::string_view header) {
  Header h;
  std::istringstream lines{std::string(header)};
  std::string line;
  bool formatSeen = false;
  while (std::getline(lines, line)) {
    std::istringstream words(line);
    std::string keyword;
    if (!(words >> keyword) || keyword == "ply" || keyword == "comment" || keyword == "obj_info" ||
        keyword == "end_header")
      continue;
    if (keyword == "format") {
      std::string f;
      words >> f;
      if (f == "ascii")
        h.format = Format::Ascii;
      else if (f == "binary_little_endian")
        h.format = Format::LittleEndian;
      else if (f == "binary_big_endian")
        h.format = Format::BigEndian;
      else
        return std::nullopt;
      formatSeen = true;
    } else if (keyword == "element") {
      Element e;
      std::string count;
      if (!(words >> e.name >> count)) return std::nullopt;
      const auto [end, ec] = std::from_chars(count.data(), count.data() + count.size(), e.count);
      if (ec != std::errc() || end != count.data() + count.size()) return std::nullopt;
      h.elements.push_back(std::move(e));
    } else if (keyword == "property") {
      if (h.elements.empty()) return std::nullopt;
      std::string type;
      words >> type;
      Property p;
      if (type == "list") {
        std::string countType, itemType;
        words >> countType >> itemType;
        const auto c = typeSize(countType), i = typeSize(itemType);
        if (!c || !i) return std::nullopt;
        p.countSize = c->first;
        p.countSigned = c->second;
        p.size = i->first;
      } else {
        const auto s = typeSize(type);
        if (!s) return std::nullopt;
        p.size = s->first;
      }
      h.elements.back().properties.push_back(p);
    }
    // Other lines are ignored, as assimp ignores them.
  }
  if (!formatSeen) return std::nullopt;
  return h;
}

[[noreturn]] void failElement(const std::string& name, const Element& e, std::uint64_t item,
                              const std::string& why) {
  throw InputError(name + ": PLY element '" + e.name + "' " + std::to_string(item) + " of " +
                   std::to_string(e.count) + ": " + why + " (the file is cut short or a count " +
                   "in it is corrupt)");
}

void checkBinary(std::string_view body, const Header& h, const std::string& name) {
  std::size_t at = 0;
  const auto readCount = [&](const Property& p) -> long double {
    std::uint64_t v = 0;
    for (int k = 0; k < p.countSize; ++k) {
      const int shift = h.format == Format::LittleEndian ? 8 * k : 8 * (p.countSize - 1 - k);
      v |= std::uint64_t(static_cast<unsigned char>(body[at + std::size_t(k)])) << shift;
    }
    at += std::size_t(p.countSize);
    if (p.countSigned && (v >> (8 * p.countSize - 1)) & 1) return -1;  // negative
    return static_cast<long double>(v);
  };
  for (const Element& e : h.elements) {
    bool hasList = false;
    std::uint64_t fixed = 0;
    for (const Property& p : e.properties) {
      hasList = hasList || p.countSize > 0;
      fixed += std::uint64_t(p.size);
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
    // Each item reads at least one count, so this loop is bounded by the file's size.
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const Property& p : e.properties) {
        const std::size_t left = body.size() - at;
        if (p.countSize == 0) {
          if (std::size_t(p.size) > left) failElement(name, e, i, "the data ends inside it");
          at += std::size_t(p.size);
          continue;
        }
        if (std::size_t(p.countSize) > left) failElement(name, e, i, "the data ends inside it");
        const long double n = readCount(p);
        if (n < 0) failElement(name, e, i, "expected a list length >= 0, got a negative one");
        const long double bytes = n * p.size;
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

void checkAscii(std::string_view body, const Header& h, const std::string& name) {
  std::size_t at = 0;
  const auto next = [&]() -> std::optional<std::string_view> {
    while (at < body.size() && std::isspace(static_cast<unsigned char>(body[at]))) ++at;
    if (at == body.size()) return std::nullopt;
    const std::size_t start = at;
    while (at < body.size() && !std::isspace(static_cast<unsigned char>(body[at]))) ++at;
    return body.substr(start, at - start);
  };
  for (const Element& e : h.elements) {
    if (e.properties.empty()) continue;
    // Each item reads at least one token, so this loop is bounded by the file's size.
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const Property& p : e.properties) {
        const auto token = next();
        if (!token) failElement(name, e, i, "the data ends before it");
        if (p.countSize == 0) continue;
        long double n = 0;
        std::int64_t whole = 0;
        const auto [end, ec] = std::from_chars(token->data(), token->data() + token->size(), whole);
        n = ec == std::errc() ? static_cast<long double>(whole) : 0;
        if (ec == std::errc::result_out_of_range || n < 0)
          failElement(name, e, i, "expected a list length >= 0, got '" + std::string(*token) + "'");
        // At least two bytes (a digit and a separator) per remaining item, but the last.
        if (n > static_cast<long double>(body.size() - at) / 2 + 1)
          failElement(name, e, i,
                      "a list of " + std::string(*token) + " items does not fit in the " +
                          std::to_string(body.size() - at) + " bytes left");
        for (std::int64_t k = 0; k < whole; ++k)
          if (!next()) failElement(name, e, i, "the data ends inside its list");
      }
    }
  }
}

}  // namespace

void checkPlyBodyBounds(std::string_view text, std::size_t bodyStart, const std::string& name) {
  if (bodyStart > text.size()) return;
  const auto header = parseHeader(text.substr(0, bodyStart));
  if (!header) return;
  const std::string_view body = text.substr(bodyStart);
  if (header->format == Format::Ascii) {
    checkAscii(body, *header, name);
  } else {
    checkBinary(body, *header, name);
  }
}

}  // namespace cdb
