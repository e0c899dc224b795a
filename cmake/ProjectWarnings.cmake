# Warnings are errors across the project. (-Wnull-dereference is left out: GCC 12
# reports false positives inside libstdc++/CLI11 inlined into our code at -O2.)
# p3at_set_warnings(target) is called
# for every target we own; third-party headers come in as SYSTEM includes.
function(p3at_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Werror
    -Wshadow -Wconversion -Wsign-conversion -Wnon-virtual-dtor
    -Wold-style-cast -Wcast-align -Woverloaded-virtual
    -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough -Wswitch-enum)
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # -Wno-restrict: GCC 12 at -O3 reports false positives inside libstdc++'s
    # std::string code (GCC bug 105329); the warning is not about our code.
    target_compile_options(${target} PRIVATE -Wduplicated-cond -Wlogical-op -Wuseless-cast -Wno-restrict)
  endif()
endfunction()
