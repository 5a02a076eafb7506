// Typed errors thrown by the library; the command-line program prints them and exits
// non-zero. Library code never calls exit().
#pragma once

#include <stdexcept>
#include <string>

namespace bsmpm {

// Where a value came from: a scene file position, or a command-line override.
struct SourceLocation {
  std::string file;  // scene path, or "--set key" for an override
  int line = 0;
  int column = 0;

  std::string str() const {
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
};

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A scene (or override) that cannot be simulated as written.
// what() reads "file:line:column: key: message".
class SceneError : public Error {
 public:
  SceneError(SourceLocation where, std::string key, std::string message)
      : Error(where.str() + ": " + (key.empty() ? "" : key + ": ") + message),
        where_(std::move(where)),
        key_(std::move(key)),
        message_(std::move(message)) {}
  const SourceLocation& where() const { return where_; }
  const std::string& key() const { return key_; }
  const std::string& message() const { return message_; }

 private:
  SourceLocation where_;
  std::string key_;
  std::string message_;
};

// Reading or writing a run file failed.
class IoError : public Error {
 public:
  using Error::Error;
};

// An input the user named cannot be read: a scene, study or run file that is missing, a
// directory, not readable, not of its kind or damaged. Bad input (exit 2), like a wrong key;
// an IoError still, for code that catches any failed read.
class InputError : public IoError {
 public:
  using IoError::IoError;
};

// There is no room left for the output: the disk (or the user's quota) is full, or the file
// reached the size limit of the process (ulimit -f). `clean()`: found before anything was
// written (io/output_space.hpp reserves the room first), so every file is whole; otherwise a
// write failed half-way.
class OutOfSpaceError : public IoError {
 public:
  OutOfSpaceError(const std::string& what, bool clean) : IoError(what), clean_(clean) {}
  bool clean() const { return clean_; }

 private:
  bool clean_;
};

// The simulation became numerically invalid (non-finite state, particle lost).
class NumericalError : public Error {
 public:
  using Error::Error;
};

// A run that the machine cannot hold (memory, disk) or that would never end (a time step
// absurdly small): refused before it starts, with the numbers.
class ResourceError : public Error {
 public:
  using Error::Error;
};

// Wrong command-line usage.
class UsageError : public Error {
 public:
  using Error::Error;
};

}  // namespace bsmpm
