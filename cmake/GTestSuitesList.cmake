# Lists the suites of a GoogleTest executable and writes CTEST_FILE, the ctest tests of
# cdbench_add_gtest_suites (cmake/GTestSuites.cmake). Run after every build of EXE (cmake -P), with
# EXE, PREFIX, EXCLUDE_FILTER, WEIGHT (COST per case), PROPERTIES (CMake code: bracketed property
# names and values), WORKING_DIRECTORY and CTEST_FILE.
cmake_minimum_required(VERSION 3.25)

# The cases EXE runs with `filter`, grouped by suite: `suites_var` the suites in order, and for
# each suite S the variable `<prefix>S` its cases' full names.
function(list_cases filter prefix suites_var)
  execute_process(COMMAND "${EXE}" --gtest_list_tests "--gtest_filter=${filter}"
                  WORKING_DIRECTORY "${WORKING_DIRECTORY}" TIMEOUT 60
                  OUTPUT_VARIABLE listing ERROR_VARIABLE errors RESULT_VARIABLE result)
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "${EXE} --gtest_list_tests failed (${result}):\n${listing}${errors}")
  endif()
  string(REPLACE ";" "\\;" listing "${listing}")
  string(REPLACE "\n" ";" lines "${listing}")
  set(suites "")
  set(suite "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^([^ #][^ ]*\\.)( |$)")  # a suite: "Name." or "Prefix/Name.  # TypeParam"
      set(suite "${CMAKE_MATCH_1}")
      list(APPEND suites "${suite}")
      set(cases_of_${suite} "")
    elseif(line MATCHES "^  ([^ ]+)" AND NOT suite STREQUAL "")  # a case, maybe "  # GetParam()"
      list(APPEND cases_of_${suite} "${suite}${CMAKE_MATCH_1}")
    endif()
  endforeach()
  foreach(s IN LISTS suites)
    set(${prefix}${s} "${cases_of_${s}}" PARENT_SCOPE)
  endforeach()
  set(${suites_var} "${suites}" PARENT_SCOPE)
endfunction()

if(EXCLUDE_FILTER STREQUAL "")
  list_cases("*" kept_ kept)
  set(excluded "")
else()
  list_cases("*-${EXCLUDE_FILTER}" kept_ kept)
  list_cases("${EXCLUDE_FILTER}" excluded_ excluded)
endif()

set(out "# Written by cmake/GTestSuitesList.cmake from ${EXE} --gtest_list_tests.\n")
# The test `name`, running by `filter` the cases listed in the variable named `cases` (its COST),
# with `labels` (property code) added.
macro(add_suite_test name filter cases labels)
  list(LENGTH ${cases} count)
  math(EXPR cost "${count} * ${WEIGHT}")
  string(APPEND out
         "add_test([==[${name}]==] [==[${EXE}]==] [==[--gtest_filter=${filter}]==])\n"
         "set_tests_properties([==[${name}]==] PROPERTIES"
         " WORKING_DIRECTORY [==[${WORKING_DIRECTORY}]==] COST ${cost}${PROPERTIES}${labels})\n")
endmacro()
foreach(suite IN LISTS kept)
  string(REGEX REPLACE "\\.$" "" name "${suite}")
  set(filter "${suite}*")
  if(NOT EXCLUDE_FILTER STREQUAL "")
    string(APPEND filter "-${EXCLUDE_FILTER}")
  endif()
  add_suite_test("${PREFIX}.${name}" "${filter}" "kept_${suite}" "")
endforeach()
foreach(suite IN LISTS excluded)
  string(REGEX REPLACE "\\.$" "" name "${suite}")
  # (A filter names a set of cases by patterns joined with ':'; here the cases themselves.)
  list(JOIN excluded_${suite} ":" filter)
  add_suite_test("${PREFIX}.${name}.release_only" "${filter}" "excluded_${suite}"
                 " LABELS release-only")
endforeach()
file(WRITE "${CTEST_FILE}" "${out}")
