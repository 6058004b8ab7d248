# Sanitizer and fuzzing builds (the CI's sanitizer stage, tools/sanitize.sh and tools/fuzz.sh).
#   -DBSSRDF_SANITIZE=ON  AddressSanitizer + UndefinedBehaviorSanitizer on the library, the tool and
#                         the tests; any report aborts the process (-fno-sanitize-recover), so ctest fails.
#   -DBSSRDF_FUZZ=ON      clang only: coverage instrumentation for libFuzzer and the tests/fuzz driver.
option(BSSRDF_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(BSSRDF_FUZZ "Build the libFuzzer driver in tests/fuzz (clang only)" OFF)
if(BSSRDF_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer -g)
  add_link_options(-fsanitize=address,undefined)
endif()
if(BSSRDF_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "BSSRDF_FUZZ needs clang (libFuzzer): configure with -DCMAKE_CXX_COMPILER=clang++")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
