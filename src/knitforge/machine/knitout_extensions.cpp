#include "knitforge/machine/knitout_extensions.h"

#include <algorithm>
#include <charconv>

#include <fmt/core.h>
#include <fmt/format.h>

#include "knitforge/util/printable.h"

namespace knitforge {

namespace {

bool is_number(std::string_view s) {
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) s.remove_prefix(1);
  int digits = 0, dots = 0;
  for (char c : s) {
    if (c >= '0' && c <= '9') ++digits;
    else if (c == '.') ++dots;
    else return false;
  }
  return digits > 0 && dots <= 1;
}

}  // namespace

std::string extension_value_problem(const ExtensionRule& rule, const std::vector<std::string>& args) {
  const std::string got =
      args.empty() ? std::string("no value") : fmt::format("'{}'", printable(fmt::format("{}", fmt::join(args, " "))));
  auto one = [&](const char* what) { return fmt::format("{} takes {}, not {}", rule.name, what, got); };
  switch (rule.value) {
    case ExtensionValue::Anything: return {};
    case ExtensionValue::NoValue: return args.empty() ? std::string() : one("no value");
    case ExtensionValue::DigitOrLetter: {
      const bool ok = args.size() == 1 && args[0].size() == 1 &&
                      ((args[0][0] >= '0' && args[0][0] <= '9') || (args[0][0] >= 'A' && args[0][0] <= 'Z'));
      return ok ? std::string() : one("one number 0-9 or letter A-Z");
    }
    case ExtensionValue::NonNegativeInteger: {
      bool ok = args.size() == 1 && !args[0].empty() &&
                std::all_of(args[0].begin(), args[0].end(), [](char c) { return c >= '0' && c <= '9'; });
      return ok ? std::string() : one("one non-negative integer");
    }
    case ExtensionValue::Number: return args.size() == 1 && is_number(args[0]) ? std::string() : one("one number");
    case ExtensionValue::OnOffAuto: {
      const bool ok = args.size() == 1 && (args[0] == "on" || args[0] == "off" || args[0] == "auto");
      return ok ? std::string() : one("on, off or auto");
    }
    case ExtensionValue::Keyword: {
      const bool ok =
          args.size() == 1 && std::find(rule.keywords.begin(), rule.keywords.end(), args[0]) != rule.keywords.end();
      return ok ? std::string() : one(fmt::format("one of {}", fmt::join(rule.keywords, ", ")).c_str());
    }
  }
  return {};
}

}  // namespace knitforge
