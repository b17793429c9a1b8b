// Shared by the fuzz targets: a broken property is a crash, which libFuzzer reports with the
// input that caused it.
#pragma once

#include <cstdio>
#include <cstdlib>

#define BLUETILE_FUZZ_CHECK(condition)                                                          \
  do {                                                                                          \
    if (!(condition)) {                                                                         \
      std::fprintf(stderr, "fuzz property failed at %s:%d: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                             \
    }                                                                                           \
  } while (0)
