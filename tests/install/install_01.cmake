# Installs talus from BUILD_DIR into a fresh prefix, then configures, builds
# and runs tests/install/consumer against it: `cmake --install` must give a
# working executable and a CMake package another project can use.
set(prefix ${WORK_DIR}/prefix)
file(REMOVE_RECURSE ${WORK_DIR})
execute_process(COMMAND ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
                RESULT_VARIABLE r OUTPUT_QUIET)
if(NOT r EQUAL 0)
  message(FATAL_ERROR "cmake --install failed")
endif()
foreach(f bin/talus include/talus/geometry/convex_polyhedron.h)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
execute_process(COMMAND ${prefix}/bin/talus --version OUTPUT_VARIABLE version RESULT_VARIABLE r)
if(NOT r EQUAL 0 OR NOT version MATCHES "^talus ")
  message(FATAL_ERROR "installed talus --version: ${version}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build
                        -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix}
                RESULT_VARIABLE r OUTPUT_QUIET)
if(NOT r EQUAL 0)
  message(FATAL_ERROR "the consumer project does not configure against the installed package")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${WORK_DIR}/build RESULT_VARIABLE r OUTPUT_QUIET)
if(NOT r EQUAL 0)
  message(FATAL_ERROR "the consumer project does not build against the installed package")
endif()
execute_process(COMMAND ${WORK_DIR}/build/consumer OUTPUT_VARIABLE out RESULT_VARIABLE r)
message(STATUS "${out}")
if(NOT r EQUAL 0 OR NOT out MATCHES "pieces of 0.25 and 0.75 m\\^3")
  message(FATAL_ERROR "the consumer printed: ${out}")
endif()
