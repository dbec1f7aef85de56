#pragma once

#include <cstdio>
#include <cstdlib>

// Invariant checks that stay active in Release builds. They guard programming errors only;
// anything a user can cause (files, options, logs) is reported through Status instead.
#define SEMCHAIN_CHECK(condition)                                                        \
  do {                                                                                   \
    if (!(condition)) {                                                                  \
      std::fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                      \
    }                                                                                    \
  } while (false)
