#include "cli/arguments.hpp"

#include <omp.h>

#include <cstdio>

#include "core/error.hpp"

namespace bsmpm::cli {

Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
                     const std::set<std::string>& options, const std::set<std::string>& repeated) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string a = args[i];
    if (a.rfind("--", 0) != 0 || a == "--") {
      positional_.push_back(a);
      continue;
    }
    std::string value;
    bool has_inline = false;
    if (const auto eq = a.find('='); eq != std::string::npos && !repeated.count(a.substr(0, eq))) {
      value = a.substr(eq + 1);
      a = a.substr(0, eq);
      has_inline = true;
    }
    if (flags.count(a)) {
      if (has_inline) throw UsageError(a + " takes no value");
      flags_.insert(a);
    } else if (options.count(a) || repeated.count(a)) {
      if (!has_inline) {
        if (i + 1 >= args.size()) throw UsageError(a + " needs a value");
        value = args[++i];
      }
      if (repeated.count(a)) repeated_[a].push_back(value);
      else options_[a] = value;
    } else {
      throw UsageError("unknown option " + a + " (see --help)");
    }
  }
}

bool Arguments::help(const std::string& text) const {
  if (!flag("--help")) return false;
  std::fputs(text.c_str(), stdout);
  return true;
}

std::string Arguments::option(const std::string& name, const std::string& fallback) const {
  const auto it = options_.find(name);
  return it == options_.end() ? fallback : it->second;
}

namespace {
// `text` read whole by `parse` (std::stod, std::stol); else a UsageError "NAME expects WHAT,
// got 'TEXT'".
template <class Parse>
auto parse_whole(const std::string& name, const std::string& text, const char* what, Parse&& parse) {
  try {
    std::size_t used = 0;
    const auto v = parse(text, &used);
    if (used != text.size()) throw std::invalid_argument("trailing");
    return v;
  } catch (const std::exception&) {
    throw UsageError(name + " expects " + what + ", got '" + text + "'");
  }
}
}  // namespace

double Arguments::number(const std::string& name, double fallback) const {
  if (!has(name)) return fallback;
  return parse_whole(name, option(name), "a number",
                     [](const std::string& t, std::size_t* used) { return std::stod(t, used); });
}

long Arguments::integer(const std::string& name, long fallback) const {
  if (!has(name)) return fallback;
  return parse_whole(name, option(name), "an integer",
                     [](const std::string& t, std::size_t* used) { return std::stol(t, used); });
}

const std::vector<std::string>& Arguments::all(const std::string& name) const {
  static const std::vector<std::string> none;
  const auto it = repeated_.find(name);
  return it == repeated_.end() ? none : it->second;
}

int apply_thread_option(const Arguments& args) {
  if (!args.has("--threads")) return omp_get_max_threads();  // all cores (or OMP_NUM_THREADS)
  const long n = args.integer("--threads", 0);
  if (n < 1 || n > 1024)
    throw UsageError("--threads expects 1 to 1024, got " + std::to_string(n) + " (without --threads: all " +
                     std::to_string(omp_get_num_procs()) + " cores)");
  omp_set_num_threads(static_cast<int>(n));
  return static_cast<int>(n);
}

}  // namespace bsmpm::cli
