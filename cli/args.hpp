// A small command-line parser: positional arguments and --options, each option declared with
// whether it takes a value. Unknown options are usage errors.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace laytracks::cli {

/// A mistake in how the command was called (exit status 2).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Args {
 public:
  /// `with_value`: options followed by a value; `flags`: options without one.
  Args(const std::vector<std::string>& argv,
       const std::set<std::string>& with_value,
       const std::set<std::string>& flags);

  const std::vector<std::string>& positional() const { return positional_; }
  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  std::optional<std::string> value(const std::string& name) const;
  /// The option's value as a positive finite number, if given.
  std::optional<double> positive_number(const std::string& name) const;
  /// The option's value as a whole number in [0, max], if given.
  std::optional<long> count(const std::string& name, long max = 1000000) const;

 private:
  std::vector<std::string> positional_;
  std::map<std::string, std::string> values_;
  std::set<std::string> flags_;
};

}  // namespace laytracks::cli
