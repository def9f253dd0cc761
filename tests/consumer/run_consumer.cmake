# ctest driver of consumer_find_package (cmake -P): install → configure → build → run, each step fatal on error.
foreach(var UNIDIST_BUILD_DIR PREFIX CONSUMER_SOURCE CONSUMER_BUILD CXX_COMPILER BUILD_TYPE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_consumer.cmake: ${var} not set")
  endif()
endforeach()
if(BUILD_TYPE STREQUAL "")
  set(BUILD_TYPE Release)
endif()

function(step name)
  message(STATUS "consumer: ${name}: ${ARGN}")
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "consumer: ${name} failed (${rc})")
  endif()
endfunction()

file(REMOVE_RECURSE "${PREFIX}" "${CONSUMER_BUILD}")
step(install "${CMAKE_COMMAND}" --install "${UNIDIST_BUILD_DIR}" --prefix "${PREFIX}" --config "${BUILD_TYPE}")
step(configure "${CMAKE_COMMAND}" -S "${CONSUMER_SOURCE}" -B "${CONSUMER_BUILD}"
     "-DCMAKE_PREFIX_PATH=${PREFIX}" "-DCMAKE_CXX_COMPILER=${CXX_COMPILER}" "-DCMAKE_BUILD_TYPE=${BUILD_TYPE}")
step(build "${CMAKE_COMMAND}" --build "${CONSUMER_BUILD}" --config "${BUILD_TYPE}")
step(run "${CONSUMER_BUILD}/unidist_consumer")
