// A small command-line parser: positional arguments, --flag, --option VALUE and repeated
// --set KEY=VALUE. Unknown options are errors.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

namespace bsmpm::cli {

class Arguments {
 public:
  // `flags` take no value; `options` take one; `repeated` may appear many times.
  Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
            const std::set<std::string>& options, const std::set<std::string>& repeated = {});

  bool flag(const std::string& name) const { return flags_.count(name) > 0; }
  // With --help: prints `text` to stdout and answers true (the command then exits 0).
  bool help(const std::string& text) const;
  bool has(const std::string& name) const { return options_.count(name) > 0; }
  std::string option(const std::string& name, const std::string& fallback = "") const;
  double number(const std::string& name, double fallback) const;
  long integer(const std::string& name, long fallback) const;
  const std::vector<std::string>& all(const std::string& name) const;
  const std::vector<std::string>& positional() const { return positional_; }

 private:
  std::set<std::string> flags_;
  std::map<std::string, std::string> options_;
  std::map<std::string, std::vector<std::string>> repeated_;
  std::vector<std::string> positional_;
};

// Sets the OpenMP thread count from --threads (1 to 1024; absent: all cores); returns it.
int apply_thread_option(const Arguments& args);

}  // namespace bsmpm::cli
