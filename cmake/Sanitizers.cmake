# P3AT_SANITIZE=ON builds everything with ASan + UBSan, and any UB aborts
# (so a test that triggers it fails instead of printing a warning).
if(P3AT_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
if(P3AT_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "P3AT_FUZZ needs clang (libFuzzer): configure with CXX=clang++")
  endif()
  # Instrument all project code for coverage so the fuzzer sees into the libraries.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
