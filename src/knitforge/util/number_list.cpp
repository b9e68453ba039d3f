#include "knitforge/util/number_list.h"

#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "knitforge/util/errors.h"

namespace knitforge {

std::vector<double> parse_number_list(const std::string& text, const std::string& context) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    try {
      size_t used = 0;
      out.push_back(std::stod(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      throw InvalidInput(fmt::format("{}: '{}' is not a number", context, item));
    }
  }
  return out;
}

}  // namespace knitforge
