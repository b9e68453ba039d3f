#include "knitforge/io/vertex_field.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "knitforge/util/atomic_file.h"
#include "knitforge/util/errors.h"

namespace knitforge {

std::vector<double> read_vertex_field(const std::string& path, int expected) {
  std::ifstream in(path);
  if (!in) throw IOError(fmt::format("{}: cannot open the field file", path));
  std::vector<double> v;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    const size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    const size_t b = line.find_last_not_of(" \t\r");
    const std::string item = line.substr(a, b - a + 1);
    size_t used = 0;
    double x = 0.0;
    try {
      x = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || !std::isfinite(x))
      throw IOError(fmt::format("{}:{}: '{}' is not one finite number (one value per vertex and line)", path, number, item));
    v.push_back(x);
  }
  if (expected >= 0 && static_cast<int>(v.size()) != expected)
    throw IOError(fmt::format("{}: {} values for a surface of {} vertices; give one value per vertex, in vertex order",
                              path, v.size(), expected));
  return v;
}

void write_vertex_field(const std::string& path, const std::vector<double>& values) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) throw InvalidInput(fmt::format("field value {} (vertex {}) is not finite", values[i], i));
  write_file_atomically(path, [&](std::ostream& os) {
    for (double x : values) os << fmt::format("{}\n", x);
  });
}

}  // namespace knitforge
