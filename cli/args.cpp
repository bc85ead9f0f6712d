#include "args.hpp"

#include <cmath>
#include <cstdlib>

namespace laytracks::cli {

Args::Args(const std::vector<std::string>& argv,
           const std::set<std::string>& with_value,
           const std::set<std::string>& flags) {
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() < 2 || a[0] != '-' || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string name = a;
    std::optional<std::string> inline_value;
    if (const auto eq = a.find('='); eq != std::string::npos) {
      name = a.substr(0, eq);
      inline_value = a.substr(eq + 1);
    }
    if (with_value.count(name)) {
      if (inline_value) {
        values_[name] = *inline_value;
      } else if (i + 1 < argv.size()) {
        values_[name] = argv[++i];
      } else {
        throw UsageError("option " + name + " needs a value");
      }
    } else if (flags.count(name) && !inline_value) {
      flags_.insert(name);
    } else {
      throw UsageError("unknown option " + a);
    }
  }
}

std::optional<std::string> Args::value(const std::string& name) const {
  const auto it = values_.find(name);
  if (it == values_.end()) return std::nullopt;
  return it->second;
}

std::optional<double> Args::positive_number(const std::string& name) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  char* end = nullptr;
  const double d = std::strtod(v->c_str(), &end);
  if (end == v->c_str() || *end != '\0' || !std::isfinite(d) || d <= 0.0) {
    throw UsageError("option " + name + " needs a positive number, got \"" + *v + "\"");
  }
  return d;
}

}  // namespace laytracks::cli

namespace laytracks::cli {

std::optional<long> Args::count(const std::string& name, long max) const {
  const auto v = value(name);
  if (!v) return std::nullopt;
  char* end = nullptr;
  const long n = std::strtol(v->c_str(), &end, 10);
  if (end == v->c_str() || *end != '\0' || n < 0 || n > max) {
    throw UsageError("option " + name + " needs a whole number from 0 to " + std::to_string(max) +
                     ", got \"" + *v + "\"");
  }
  return n;
}

}  // namespace laytracks::cli
