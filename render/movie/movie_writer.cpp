#include "movie/movie_writer.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>

#include "core/error.hpp"

namespace bsmpm::render {

namespace {

// What dlopen() or dlsym() last reported (dlerror() may return null).
std::string last_dl_error() {
  const char* message = dlerror();
  return message ? message : "no reason given";
}

// The module beside the running program (build/render/ holds both), loaded once and kept:
// the encoders it makes run its code until they are destroyed.
OpenMovieFunction* movie_module_entry() {
  static std::once_flag once;
  static OpenMovieFunction* entry = nullptr;
  static std::string failure;
  std::call_once(once, [] {
    std::error_code ec;
    const std::filesystem::path program = std::filesystem::canonical("/proc/self/exe", ec);
    const std::string module = (ec ? std::filesystem::path(kMovieModuleName)
                                   : program.parent_path() / kMovieModuleName)
                                   .string();
    void* handle = dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      failure = "cannot load the movie encoder " + module + ": " + last_dl_error();
      return;
    }
    entry = reinterpret_cast<OpenMovieFunction*>(dlsym(handle, kOpenMovieSymbol));
    if (entry == nullptr) failure = module + " has no " + kOpenMovieSymbol + ": " + last_dl_error();
  });
  if (entry == nullptr) throw IoError(failure);
  return entry;
}

}  // namespace

std::unique_ptr<MovieWriter> open_movie(const std::string& path, const MovieSettings& settings) {
  return std::unique_ptr<MovieWriter>(movie_module_entry()(path, settings));
}

}  // namespace bsmpm::render
