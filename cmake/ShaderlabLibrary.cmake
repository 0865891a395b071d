# One shape for every library of the project (docs/architecture.md), after filament's libs/<name>/:
#   <dir>/include/<prefix>/<name>/*.h   public headers: what other libraries may include
#   <dir>/src/                          private sources and headers: nothing outside may include them
#   <dir>/tests/*_test.cpp              the library's own tests, in a test program of its own
# The include directory of a library reaches only the targets that link it, so an include that
# runs the wrong way (the metrics including a report, the scene loader including the renderer)
# fails to compile instead of becoming a habit.

# shaderlab_library(<target> [EXTRA_SOURCES files...]): a static library from src/*.cpp.
function(shaderlab_library target)
  cmake_parse_arguments(ARG "" "" "EXTRA_SOURCES" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/*.cpp)
  add_library(${target} STATIC ${sources} ${ARG_EXTRA_SOURCES})
  target_include_directories(${target} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include
                                       PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  shaderlab_warnings(${target})
endfunction()

# shaderlab_test_environment(): the sanitizer options every test of the current folder runs with
# under SHADERLAB_SANITIZE (see the top-level CMakeLists.txt); nothing otherwise.
function(shaderlab_test_environment)
  if(SHADERLAB_SANITIZER_TEST_ENV)
    set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES ${SHADERLAB_SANITIZER_TEST_ENV})
  endif()
endfunction()

# shaderlab_library_tests(<test program> LINK <targets...> [PREFIXED_RUNS <prefix>=<env>...]
#                         [TIMEOUT seconds]): tests/*_test.cpp of the current library as one
# GoogleTest program linking only <targets> (the library itself and what its tests need), with the
# source tree's and the test data's folders compiled in. Each PREFIXED_RUNS entry discovers the
# whole program once more under a test-name prefix with one environment variable set.
function(shaderlab_library_tests program)
  if(NOT SHADERLAB_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(ARG "" "TIMEOUT" "LINK;PREFIXED_RUNS" ${ARGN})
  file(GLOB tests CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/tests/*_test.cpp)
  add_executable(${program} ${tests})
  target_link_libraries(${program} PRIVATE ${ARG_LINK} GTest::gtest GTest::gtest_main)
  target_include_directories(${program} PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/tests)
  target_compile_definitions(${program} PRIVATE
    SHADERLAB_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SHADERLAB_TEST_DATA="${PROJECT_SOURCE_DIR}/tests/data")
  shaderlab_warnings(${program})
  shaderlab_test_environment()
  set(properties)
  if(ARG_TIMEOUT)
    set(properties PROPERTIES TIMEOUT ${ARG_TIMEOUT})
  endif()
  gtest_discover_tests(${program} DISCOVERY_TIMEOUT 60 ${properties})
  foreach(run ${ARG_PREFIXED_RUNS})
    string(REPLACE "=" ";" parts "${run}")
    list(GET parts 0 prefix)
    list(SUBLIST parts 1 -1 env)
    string(REPLACE ";" "=" env "${env}")
    gtest_discover_tests(${program} DISCOVERY_TIMEOUT 60 TEST_PREFIX "${prefix}."
                         PROPERTIES ENVIRONMENT "${env}" ${properties})
  endforeach()
endfunction()
