# -DHEADINGD_FUZZ=ON: a tree of libFuzzer targets only (tests/fuzz), built by clang with
# AddressSanitizer and UndefinedBehaviorSanitizer in every translation unit, the libraries
# included, so that a bad read anywhere under a parser is reported. tools/scripts/fuzz.sh
# configures it (in build/fuzz); the main build stays with gcc.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "HEADINGD_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
endif()
# fuzzer-no-link: coverage instrumentation for libFuzzer in every object; only the targets
# link libFuzzer's main (tests/fuzz/CMakeLists.txt). No recovery: the first report stops
# the run, so libFuzzer saves the input that caused it.
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
add_link_options(-fsanitize=address,undefined)
