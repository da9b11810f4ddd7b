#include "sim/dataset/pcd_header.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>

namespace bimloc::sim {
namespace {

[[noreturn]] void pcdFail(const std::string& path, const std::string& what) { throw std::runtime_error(path + ": " + what); }

std::size_t count(const std::string& path, const std::string& key, const std::string& text) {
  std::size_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || value > (std::size_t(1) << 40))
    pcdFail(path, key + " '" + text + "' is not a count");
  return value;
}

}  // namespace

PcdHeader readPcdHeader(const std::string& path, std::istream& in, std::size_t file_size) {
  std::map<std::string, std::vector<std::string>> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string key, value;
    ss >> key;
    while (ss >> value) header[key].push_back(value);
    if (key == "DATA") break;
    if (header.size() > 32) break;  // not a PCD header: stop before reading a binary file as lines
  }
  const auto one = [&](const std::string& key) -> const std::string& {
    if (header[key].size() != 1) pcdFail(path, "not a PCD file: no single " + key + " value in the header");
    return header[key][0];
  };
  // The format's versions (PCL writes ".7" or "0.7"); an absent VERSION is tolerated, a garbled one
  // says the header is damaged.
  if (header.count("VERSION")) {
    static const std::vector<std::string> known{"0.7", ".7", "0.6", ".6", "0.5", ".5"};
    if (std::find(known.begin(), known.end(), one("VERSION")) == known.end())
      pcdFail(path, "VERSION '" + one("VERSION") + "' is none of the PCD format's 0.5, 0.6, 0.7");
  }
  PcdHeader h;
  h.fields = header["FIELDS"];
  const auto& sizes = header["SIZE"];
  const auto& types = header["TYPE"];
  if (h.fields.empty() || sizes.size() != h.fields.size() || (!types.empty() && types.size() != h.fields.size()))
    pcdFail(path, "not a PCD file: FIELDS, SIZE and TYPE do not match");
  h.points = count(path, "POINTS", one("POINTS"));
  if (!header["WIDTH"].empty() && !header["HEIGHT"].empty() &&
      count(path, "WIDTH", one("WIDTH")) * count(path, "HEIGHT", one("HEIGHT")) != h.points)
    pcdFail(path, "POINTS " + std::to_string(h.points) + " is not WIDTH x HEIGHT");
  for (const auto& v : header["VIEWPOINT"]) {  // the sensor's pose: seven finite numbers
    double value = 0.0;
    const auto [ptr, ec] = std::from_chars(v.data(), v.data() + v.size(), value);
    if (ec != std::errc() || ptr != v.data() + v.size() || !std::isfinite(value))
      pcdFail(path, "VIEWPOINT value '" + v + "' is not a finite number");
  }
  for (const auto& c : header["COUNT"])
    if (c != "1") pcdFail(path, "COUNT other than 1 is not supported");
  bool found = false;
  for (std::size_t i = 0; i < h.fields.size(); ++i) {
    const std::size_t size = count(path, "SIZE", sizes[i]);
    if (size == 0 || size > 8) pcdFail(path, "SIZE '" + sizes[i] + "' is not 1, 2, 4 or 8");
    if (h.fields[i] == "x" && i + 2 < h.fields.size() && h.fields[i + 1] == "y" && h.fields[i + 2] == "z") {
      for (std::size_t k = i; k < i + 3; ++k)
        if (sizes[k] != "4" || (!types.empty() && types[k] != "F")) pcdFail(path, "x y z are not 4-byte floats");
      h.x_offset = h.stride, h.x_index = i, found = true;
    }
    h.stride += size;
  }
  if (!found) pcdFail(path, "no consecutive x y z fields");
  const std::string& data = one("DATA");
  if (data != "binary" && data != "ascii") pcdFail(path, "unsupported DATA '" + data + "'");
  h.binary = data == "binary";
  const auto at = in.tellg();
  if (at < 0) pcdFail(path, "truncated header");
  h.data_offset = static_cast<std::size_t>(at);
  const std::size_t rest = file_size - std::min(file_size, h.data_offset);
  if (h.binary && rest != h.points * h.stride)
    pcdFail(path, "the header's " + std::to_string(h.points) + " points of " + std::to_string(h.stride) + " bytes need " +
                   std::to_string(h.points * h.stride) + " bytes of data, the file has " + std::to_string(rest));
  if (!h.binary && h.points * h.fields.size() * 2 > rest + 1)  // at least a digit and a blank a value
    pcdFail(path, "the header's " + std::to_string(h.points) + " points do not fit in the file's " + std::to_string(rest) +
                   " bytes of data");
  return h;
}

}  // namespace bimloc::sim
