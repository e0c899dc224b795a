# The sanitized build compiles in batches (CMAKE_UNITY_BUILD, scripts/build.sh
# asan): one translation unit per few source files of a target, so the heavy
# headers (Eigen, doctest, nlohmann/json, CLI11, yaml) are parsed once per
# batch instead of once per file. Why only there: CI's 40 minutes are mostly
# the two builds, and the sanitized one is the one whose objects nobody ships;
# the release build stays one file per unit, so a file that compiles only
# because a batch-mate included a header still fails there.
#
# A batch is one file as far as the compiler goes: two files whose
# file-local helpers share a name (an anonymous namespace's kDegToRad, a
# `using Json = ...`) do not compile together. Those files are compiled on
# their own, listed here by their path from the source root. A new file that
# collides fails the sanitized build with "redefinition of ..."; add it here
# (or give the helper a name of its own).
set(P3AT_UNITY_SKIP
  executive/src/realtime_loop.cpp
  hal/tcp/tcp_listener.cpp
  launch_gate/src/launch_session.cpp
  report/src/report_run.cpp
  sim_hal/src/firmware_emulator.cpp
  sim_hal/src/sim_robot.cpp
  team_sim/src/part_file.cpp
  verifier/src/calibration/motion_fit.cpp
  verifier/src/calibration/ramp_fit.cpp
  verifier/src/engine/path_stepper.cpp
  verifier/src/models/models_writer.cpp
  verifier/src/mog/operations.cpp
  tests/unit/can/test_accessory_codecs.cpp
  tests/unit/can/test_accessory_hub.cpp
  tests/unit/can/test_guarded_drive_base.cpp
  tests/unit/common/test_yaml_map.cpp
  tests/unit/examples/test_more_examples.cpp
  tests/unit/gate/test_gate_session.cpp
  tests/unit/gate/test_pre_launch_check.cpp
  tests/unit/hal/test_serial_stream.cpp
  tests/unit/mission/test_messages.cpp
  tests/unit/report/test_report_page.cpp
)

# Marks the listed files of every target under `dir` (and its subdirectories)
# as compiled on their own. Source file properties belong to the directory
# that made the target, hence TARGET_DIRECTORY.
function(p3at_unity_skip_listed dir)
  get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
  foreach(target IN LISTS targets)
    get_target_property(sources ${target} SOURCES)
    get_target_property(target_dir ${target} SOURCE_DIR)
    if(NOT sources)
      continue()
    endif()
    foreach(source IN LISTS sources)
      if(source MATCHES "\\$<")
        continue()
      endif()
      get_filename_component(absolute ${source} ABSOLUTE BASE_DIR ${target_dir})
      file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${absolute})
      if(relative IN_LIST P3AT_UNITY_SKIP)
        set_source_files_properties(${absolute} TARGET_DIRECTORY ${target} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
      endif()
    endforeach()
  endforeach()
  get_property(subdirectories DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
  foreach(subdirectory IN LISTS subdirectories)
    p3at_unity_skip_listed(${subdirectory})
  endforeach()
endfunction()
