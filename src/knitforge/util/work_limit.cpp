#include "knitforge/util/work_limit.h"

#include <cmath>

#include <fmt/core.h>

#include "knitforge/util/errors.h"

namespace knitforge {

std::string readable_count(double n) {
  if (!std::isfinite(n)) return n > 0 ? "infinitely many" : "an undefined number of";
  const double a = std::abs(n);
  if (a < 1e6) {
    const auto i = static_cast<int64_t>(std::llround(a));
    std::string digits = std::to_string(i), out;
    for (size_t k = 0; k < digits.size(); ++k) {
      if (k > 0 && (digits.size() - k) % 3 == 0) out += ',';
      out += digits[k];
    }
    return (n < 0 ? "-" : "") + out;
  }
  if (a < 1e9) return fmt::format("{:.3g} million", n / 1e6);
  if (a < 1e12) return fmt::format("{:.3g} billion", n / 1e9);
  return fmt::format("{:.2g}", n);
}

std::string readable_bytes(double bytes) {
  if (!std::isfinite(bytes)) return "unbounded memory";
  if (bytes < 1e3) return fmt::format("{:.0f} bytes", bytes);
  if (bytes < 1e6) return fmt::format("{:.3g} kB", bytes / 1e3);
  if (bytes < 1e9) return fmt::format("{:.3g} MB", bytes / 1e6);
  if (bytes < 1e12) return fmt::format("{:.3g} GB", bytes / 1e9);
  return fmt::format("{:.2g} TB", bytes / 1e12);
}

void check_work(const WorkEstimate& e) {
  if (!(e.limit > 0.0)) throw InvalidInput(fmt::format("{}: the work limit must be positive", e.what));
  if (e.count <= e.limit) return;  // also false for NaN: refused below
  const std::string memory =
      e.bytes_per_unit > 0.0 ? fmt::format(" (about {})", readable_bytes(e.count * e.bytes_per_unit)) : "";
  throw InvalidInput(fmt::format("{} would need about {} {}{}, more than the limit of {}; {}", e.what,
                                 readable_count(e.count), e.unit, memory, readable_count(e.limit), e.remedy));
}

}  // namespace knitforge
