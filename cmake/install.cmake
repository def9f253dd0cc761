# Install and export: libraries, public headers and the `unidist` command, plus a relocatable
# unidistConfig.cmake so that find_package(unidist) gives unidist::core, ::adapters, ::bullet, ::ode
# (and ::raster when it was built).
include(CMakePackageConfigHelpers)

get_filename_component(_unidist_root "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)
set(UNIDIST_INSTALL_CMAKEDIR "${CMAKE_INSTALL_LIBDIR}/cmake/unidist" CACHE STRING
    "Where unidistConfig.cmake is installed (relative to the prefix)")
# The exported plugin targets link PkgConfig::BULLET / PkgConfig::ODE: the config re-creates them from the
# same pkg-config modules this build used.
if(UNIDIST_BULLET_DOUBLE)
  set(UNIDIST_BULLET_PC_MODULE "bullet-float64>=3.24")
else()
  set(UNIDIST_BULLET_PC_MODULE "bullet>=3.24")
endif()
set(UNIDIST_ODE_PC_MODULE "ode>=0.16")

set(_unidist_targets unidist_core unidist_adapters unidist_adapters_bullet unidist_adapters_ode unidist_bullet unidist_ode
                     unidist)
set(_unidist_header_dirs core/include adapters/include adapters/bullet/include adapters/ode/include
                         plugin/bullet/include plugin/ode/include)
# The raster target (OSMesa, qhull) when it was built: the config then re-creates its pkg-config targets too.
set(UNIDIST_RASTER_PC_MODULES "")
if(UNIDIST_HAVE_RASTER)
  list(APPEND _unidist_targets unidist_raster)
  list(APPEND _unidist_header_dirs core/raster/include)
  set(UNIDIST_RASTER_PC_MODULES "\"OSMESA;osmesa\" \"QHULL;qhull_r\"")
endif()
install(TARGETS ${_unidist_targets}
        EXPORT unidistTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
foreach(_dir ${_unidist_header_dirs})
  install(DIRECTORY "${_unidist_root}/${_dir}/" DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(EXPORT unidistTargets NAMESPACE unidist:: FILE unidistTargets.cmake DESTINATION ${UNIDIST_INSTALL_CMAKEDIR})

configure_package_config_file("${_unidist_root}/cmake/unidistConfig.cmake.in"
                              "${PROJECT_BINARY_DIR}/unidistConfig.cmake"
                              INSTALL_DESTINATION ${UNIDIST_INSTALL_CMAKEDIR})
# 0.x: a minor release may break the API, so only the same major.minor is compatible.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/unidistConfigVersion.cmake"
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/unidistConfig.cmake" "${PROJECT_BINARY_DIR}/unidistConfigVersion.cmake"
        DESTINATION ${UNIDIST_INSTALL_CMAKEDIR})
