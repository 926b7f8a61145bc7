// Entry point shared by all benchmark files of bench/.
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
