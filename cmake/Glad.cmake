# Generates the OpenGL 4.5 core loader with Debian's glad 2 generator at configure time.
# --reproducible makes glad use the Khronos XML it ships instead of fetching the newest, so the
# build is offline and the same on every machine. One loader serves OSMesa, EGL and GLFW: each
# backend hands gladLoadGL its own get-proc-address function.
find_program(GLAD_EXECUTABLE glad HINTS /usr/bin)
if(NOT GLAD_EXECUTABLE)
  message(FATAL_ERROR "glad generator not found: install the Debian package python3-glad")
endif()
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
set(GLAD_ARGS --reproducible --quiet --api gl:core=4.5 --extensions= --out-path ${GLAD_OUT} c --loader)
if(NOT EXISTS ${GLAD_OUT}/src/gl.c OR NOT "${GLAD_ARGS}" STREQUAL "${GLAD_LAST_ARGS}")
  execute_process(COMMAND ${GLAD_EXECUTABLE} ${GLAD_ARGS}
                  RESULT_VARIABLE glad_rc OUTPUT_VARIABLE glad_log ERROR_VARIABLE glad_log)
  if(NOT glad_rc EQUAL 0)
    message(FATAL_ERROR "glad failed (${glad_rc}):\n${glad_log}")
  endif()
  set(GLAD_LAST_ARGS "${GLAD_ARGS}" CACHE INTERNAL "")
endif()
add_library(shaderlab_glad STATIC ${GLAD_OUT}/src/gl.c)
target_include_directories(shaderlab_glad SYSTEM PUBLIC ${GLAD_OUT}/include)
set_target_properties(shaderlab_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
