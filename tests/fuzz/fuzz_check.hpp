#pragma once
// An invariant of a fuzz target: when it fails, the input is a finding. libFuzzer treats
// abort() as a crash and saves the input (crash-<sha1>) for the regression corpus.
#include <cstdio>
#include <cstdlib>

#define FUZZ_CHECK(condition)                                                                \
  do {                                                                                       \
    if (!(condition)) {                                                                      \
      std::fprintf(stderr, "%s:%d: invariant failed: %s\n", __FILE__, __LINE__, #condition); \
      std::abort();                                                                          \
    }                                                                                        \
  } while (false)
