// TEMPORARY profiling (not for main): CPU time per phase of the projection.
#pragma once
#include <time.h>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <map>
namespace bsmpm::prof {
inline double now() { timespec t; clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
struct Table {
  std::map<std::string, double> s; long steps = 0; long iters = 0; long solves = 0;
  ~Table() {
    if (!std::getenv("BSMPM_PROF")) return;
    std::fprintf(stderr, "PROF steps %ld solves %ld iterations/solve %.2f\n", steps, solves, solves ? double(iters) / solves : 0.0);
    double tot = 0; for (auto& [k, v] : s) tot += v;
    for (auto& [k, v] : s) std::fprintf(stderr, "PROF %-14s %9.3f ms/step\n", k.c_str(), 1e3 * v / std::max(1L, steps));
    std::fprintf(stderr, "PROF %-14s %9.3f ms/step\n", "total", 1e3 * tot / std::max(1L, steps));
  }
};
inline Table& table() { static Table t; return t; }
struct Clock { double t = now(); void lap(const char* k) { double n = now(); table().s[k] += n - t; t = n; } };
}
