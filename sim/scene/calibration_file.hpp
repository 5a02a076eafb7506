// The calibration file this machine keeps: the rates `bsmpm bench` measured
// (run_calibration.hpp), newest per key, as a JSON array of flat objects. It lives in
// $BSMPM_CALIBRATION, else $XDG_CACHE_HOME/bsmpm/calibration.json, else
// ~/.cache/bsmpm/calibration.json. Written through a temporary file and a rename, so a reader
// never sees half of it. A file that cannot be read is a warning, never a failure: it only
// makes a prediction.
#pragma once

#include <string>
#include <vector>

#include "scene/run_calibration.hpp"

namespace bsmpm {

// Where the calibration is kept; empty when neither the environment nor a home says.
std::string calibration_path();

// This machine: the CPU model of /proc/cpuinfo ("unknown" without one) and its hardware threads.
MachineIdentity this_machine();

struct CalibrationFile {
  std::vector<CalibrationRecord> records;  // none when the file is missing or unreadable
  std::string warning;                     // why an existing file was not read (names the file)
};

CalibrationFile read_calibration(const std::string& path);

// Adds `fresh` to the file (replacing the older record of its key), creating its directory.
// Throws IoError when it cannot be written; returns the reading warning, if any (an unreadable
// file is replaced).
std::string record_calibration(const std::string& path, const CalibrationRecord& fresh);

}  // namespace bsmpm
