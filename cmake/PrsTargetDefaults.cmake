# Shared compile settings: warnings everywhere, sanitizers when PRS_SANITIZE is on,
# and a helper that turns a list of *_test.cc files into one GoogleTest program.

if(PRS_SANITIZE)
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()

# Applies the project's warning flags and the src/ include root to TARGET.
function(prs_target_defaults target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-sign-compare)
  target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR}/src)
endfunction()

# prs_add_test(NAME SOURCES... LIBS ...): one GoogleTest binary, discovered by CTest.
function(prs_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  prs_target_defaults(${name})
  target_link_libraries(${name} PRIVATE ${ARG_LIBS} GTest::gtest GTest::gtest_main)
  # Reachable sets computed by one test are read from this build's own cache by the others
  # (and never from the user's ~/.cache): see lang::DefaultCacheDir. Two properties, not one
  # ENVIRONMENT list: gtest_discover_tests splits a list into separate property arguments, and
  # everything after the first item was silently dropped.
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60
                       PROPERTIES ENVIRONMENT "PRS_SOURCE_DIR=${PROJECT_SOURCE_DIR}"
                       ENVIRONMENT_MODIFICATION "PRS_CACHE_DIR=set:${PROJECT_BINARY_DIR}/test_reach_cache")
endfunction()
