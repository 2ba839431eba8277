#include "support/bench_support.hpp"
