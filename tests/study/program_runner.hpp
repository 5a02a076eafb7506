// Running the bsmpm program (and the scripts around it) from the study tests.
#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.hpp"  // run_shell

namespace bsmpm::test {

// Runs a shell command with stdout and stderr into `log`; returns its exit status, or -1 if
// it did not exit normally.
inline int run_command(const std::string& command, const std::filesystem::path& log) {
  return run_shell(command, log).status;
}

// A CSV without quoted fields: the header and one map per row.
struct Csv {
  std::vector<std::string> header;
  std::vector<std::map<std::string, std::string>> rows;
  double number(std::size_t row, const std::string& column) const { return std::stod(rows.at(row).at(column)); }
};

inline Csv read_csv(const std::filesystem::path& p) {
  auto split = [](const std::string& line) {
    std::vector<std::string> out;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) out.push_back(field);
    return out;
  };
  Csv csv;
  std::ifstream in(p);
  std::string line;
  if (!std::getline(in, line)) return csv;
  csv.header = split(line);
  while (std::getline(in, line)) {
    const auto fields = split(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < csv.header.size(); ++i) row[csv.header[i]] = i < fields.size() ? fields[i] : "";
    csv.rows.push_back(row);
  }
  return csv;
}

}  // namespace bsmpm::test
