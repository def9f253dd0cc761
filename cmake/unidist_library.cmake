# unidist_library(<export name> SOURCES ... [PUBLIC_LINKS ...] [PRIVATE_LINKS ...]): one library of the project,
# target unidist_<name> with alias unidist::<name>, its public headers in include/ beside the CMakeLists and its
# private headers in src/, C++17, our warnings as errors.
function(unidist_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LINKS;PRIVATE_LINKS" ${ARGN})
  set(target unidist_${name})
  add_library(${target} ${ARG_SOURCES})
  add_library(unidist::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name} OUTPUT_NAME ${target})
  target_compile_features(${target} PUBLIC cxx_std_17)
  target_include_directories(${target}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_LINKS} PRIVATE ${ARG_PRIVATE_LINKS})
  target_compile_options(${target} PRIVATE ${UNIDIST_WARNINGS})
endfunction()
