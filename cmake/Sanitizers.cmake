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

# p3at_optimise_when_sanitized(target): the sanitized build is -O0 (it compiles
# fastest, scripts/build.sh), but the libraries whose loops the tests spend
# their time in (the verifier's Eigen engine, the simulator, the executive's
# cycle) run about ten times slower at -O0 than at -O1 under ASan:
# verifier_test_stuck_paths 153 s -> 17 s, verifier_test_engine 56 s -> 6 s
# (same machine, one after the other). So those few targets get -O1, which
# comes after the build type's -O0 on the command line and wins; ASan and
# UBSan instrument them all the same.
function(p3at_optimise_when_sanitized target)
  if(P3AT_SANITIZE)
    target_compile_options(${target} PRIVATE -O1)
  endif()
endfunction()
