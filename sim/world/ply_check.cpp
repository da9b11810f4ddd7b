#include "sim/world/ply_check.hpp"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace bimloc::sim {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) { throw std::runtime_error(path + ": " + what); }

std::size_t typeSize(const std::string& type) {
  static const std::map<std::string, std::size_t> sizes{
      {"char", 1},  {"uchar", 1},  {"int8", 1},  {"uint8", 1},  {"short", 2},   {"ushort", 2},  {"int16", 2},
      {"uint16", 2}, {"int", 4},   {"uint", 4},  {"float", 4},  {"int32", 4},   {"uint32", 4},  {"float32", 4},
      {"double", 8}, {"float64", 8}};
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

struct Property {
  std::string name;
  std::size_t size = 0;        // of a scalar, or of a list's items
  std::size_t count_size = 0;  // of a list's count, 0 for a scalar
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

std::uint64_t littleEndian(const unsigned char* p, std::size_t size) {
  std::uint64_t v = 0;
  for (std::size_t k = size; k-- > 0;) v = (v << 8) | p[k];
  return v;
}

// A face is a polygon: fewer than 3 corners is no surface, and assimp's triangulation aborts the
// process on such a face (an ai_assert) instead of failing, whatever the format.
void requirePolygon(const std::string& path, std::uint64_t face, std::uint64_t corners) {
  if (corners < 3)
    fail(path, "face " + std::to_string(face) + " has " + std::to_string(corners) + " vertex indices; a face needs at least 3");
}

// An ASCII body, walked as the binary one: every element's numbers present, every face a polygon of
// existing vertices, nothing after the last element.
void checkAsciiBody(const std::string& path, const std::string& data, std::size_t at, const std::vector<Element>& elements) {
  std::istringstream body(data.substr(at));
  std::uint64_t vertices = 0;
  std::string word;
  for (const Element& e : elements) {
    if (e.name == "vertex") vertices = e.count;
    for (std::uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        const auto number = [&](double& v) {
          if (!(body >> word)) fail(path, "truncated: element " + e.name + " " + std::to_string(i) + " is cut short");
          char* stop = nullptr;
          v = std::strtod(word.c_str(), &stop);
          if (stop == word.c_str() || *stop != '\0')
            fail(path, "element " + e.name + " " + std::to_string(i) + ": '" + word.substr(0, 40) + "' is not a number");
        };
        double v = 0;
        number(v);
        if (p.count_size == 0) continue;
        if (!(v >= 0 && v <= 1e6 && v == std::floor(v)))
          fail(path, "element " + e.name + " " + std::to_string(i) + ": a list of '" + word.substr(0, 40) + "' items");
        const auto n = static_cast<std::uint64_t>(v);
        if (e.name == "face") requirePolygon(path, i, n);
        for (std::uint64_t k = 0; k < n; ++k) {
          number(v);
          if (e.name == "face" && !(v >= 0 && v < static_cast<double>(vertices) && v == std::floor(v)))
            fail(path, "face " + std::to_string(i) + " names a vertex past the " + std::to_string(vertices) + " vertices");
        }
      }
  }
  if (body >> word) fail(path, "text after the last element: '" + word.substr(0, 40) + "'");
}

}  // namespace

void checkPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string data = buffer.str();
  const auto end = data.find("\nend_header\n");
  if (data.compare(0, 4, "ply\n") != 0 || end == std::string::npos || end > 65536)
    fail(path, "not a PLY file (no 'ply' line first, or no end_header line)");
  std::istringstream header(data.substr(4, end - 4));
  std::vector<Element> elements;
  std::string format, line;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "format") {
      std::string version;
      words >> format >> version;
      if ((format != "binary_little_endian" && format != "ascii") || version != "1.0")
        fail(path, "unsupported PLY format '" + line + "'");
    } else if (key == "element") {
      Element e;
      if (!(words >> e.name >> e.count) || e.count > (std::uint64_t(1) << 32)) fail(path, "bad PLY line '" + line + "'");
      elements.push_back(e);
    } else if (key == "property") {
      std::string type, name;
      words >> type;
      Property p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        p.count_size = typeSize(count_type), p.size = typeSize(item_type);
        if (p.count_size == 0 || p.count_size > 4) p.size = 0;
      } else {
        p.size = typeSize(type);
      }
      words >> p.name;
      if (elements.empty() || p.size == 0 || p.name.empty()) fail(path, "bad PLY line '" + line + "'");
      elements.back().properties.push_back(p);
    } else if (key != "comment" && key != "obj_info" && !key.empty()) {
      fail(path, "bad PLY header line '" + line + "'");
    }
  }
  if (format.empty()) fail(path, "no format line in the PLY header");
  std::size_t at = end + std::strlen("\nend_header\n");
  if (format == "ascii") return checkAsciiBody(path, data, at, elements);
  std::uint64_t vertices = 0;
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  for (const Element& e : elements) {
    if (e.name == "vertex") vertices = e.count;
    if (e.properties.empty()) continue;  // nothing stored: no byte to read, however many
    for (std::uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        std::uint64_t n = 1;
        if (p.count_size > 0) {
          if (at + p.count_size > data.size()) fail(path, "truncated: element " + e.name + " " + std::to_string(i) + " is cut short");
          n = littleEndian(bytes + at, p.count_size);
          at += p.count_size;
        }
        if (at + n * p.size > data.size()) fail(path, "truncated: element " + e.name + " " + std::to_string(i) + " is cut short");
        if (p.count_size > 0 && e.name == "face") requirePolygon(path, i, n);
        if (p.count_size > 0 && e.name == "face" && (p.size == 4 || p.size == 2 || p.size == 1))
          for (std::uint64_t k = 0; k < n; ++k)
            if (littleEndian(bytes + at + k * p.size, p.size) >= vertices)
              fail(path, "face " + std::to_string(i) + " names a vertex past the " + std::to_string(vertices) + " vertices");
        at += n * p.size;
      }
  }
  if (at != data.size()) fail(path, std::to_string(data.size() - at) + " bytes after the last element");
}

}  // namespace bimloc::sim
