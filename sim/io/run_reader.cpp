#include "io/run_reader.hpp"
