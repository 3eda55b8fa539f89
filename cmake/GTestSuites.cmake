# One ctest test per GoogleTest suite of an executable, instead of one per case
# (gtest_discover_tests): a case in a process of its own pays the process, the scenes it loads and
# the GL context it makes every time (0.2 s a GL case in a release build, 0.4 s under ASan), which
# was a third of the test stages' time on 2 cores. The suites are listed after every build of the
# executable (cmake/GTestSuitesList.cmake), so a suite added later is registered without a word
# here; a suite's cases run in the order GoogleTest gives them, in one process.
#
#   cdbench_add_gtest_suites(TARGET exe PREFIX name [EXCLUDE_FILTER patterns] [WEIGHT n]
#                            [PROPERTIES prop value ...])
#
# Each suite S of `exe` becomes the test PREFIX.S, running the cases of S not matched by
# EXCLUDE_FILTER (Google Test filter patterns joined by ':'), and, when some of S's cases match it,
# PREFIX.S.release_only running those, with the ctest label release-only. COST is the number of
# cases times WEIGHT (1 unless given; ctest starts the costliest first when it has no times
# measured); PROPERTIES are set on every test (ENVIRONMENT as one entry).
function(cdbench_add_gtest_suites)
  cmake_parse_arguments(PARSE_ARGV 0 arg "" "TARGET;PREFIX;EXCLUDE_FILTER;WEIGHT" "PROPERTIES")
  if(NOT arg_WEIGHT)
    set(arg_WEIGHT 1)
  endif()
  set(ctest_file "${CMAKE_CURRENT_BINARY_DIR}/${arg_TARGET}_suites.cmake")
  set(include_file "${CMAKE_CURRENT_BINARY_DIR}/${arg_TARGET}_suites_include.cmake")
  # The properties as CMake code for the script (a list of lists does not survive -D).
  set(properties "")
  foreach(p IN LISTS arg_PROPERTIES)
    string(APPEND properties " [==[${p}]==]")
  endforeach()
  add_custom_command(
    TARGET ${arg_TARGET} POST_BUILD
    BYPRODUCTS "${ctest_file}"
    COMMAND "${CMAKE_COMMAND}"
            -D "EXE=$<TARGET_FILE:${arg_TARGET}>"
            -D "PREFIX=${arg_PREFIX}"
            -D "EXCLUDE_FILTER=${arg_EXCLUDE_FILTER}"
            -D "WEIGHT=${arg_WEIGHT}"
            -D "PROPERTIES=${properties}"
            -D "WORKING_DIRECTORY=${CMAKE_CURRENT_BINARY_DIR}"
            -D "CTEST_FILE=${ctest_file}"
            -P "${PROJECT_SOURCE_DIR}/cmake/GTestSuitesList.cmake"
    VERBATIM)
  # Before the first build there is nothing listed yet: a placeholder test says so.
  file(WRITE "${include_file}"
       "if(EXISTS \"${ctest_file}\")\n"
       "  include(\"${ctest_file}\")\n"
       "else()\n"
       "  add_test([==[${arg_PREFIX}.NOT_BUILT]==] [==[${arg_TARGET} is not built]==])\n"
       "endif()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${include_file}")
endfunction()
