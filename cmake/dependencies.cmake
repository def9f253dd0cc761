# Every outside dependency, found once, from Debian's packages. A missing one stops configure with the
# package to install. Nothing is downloaded at configure time.
find_package(PkgConfig)
if(NOT PkgConfig_FOUND)
  message(FATAL_ERROR "pkg-config not found: apt-get install pkg-config")
endif()

function(unidist_require_pc prefix module debpkg)
  pkg_check_modules(${prefix} QUIET IMPORTED_TARGET GLOBAL ${module})
  if(NOT ${prefix}_FOUND)
    message(FATAL_ERROR "${module} not found: apt-get install ${debpkg}")
  endif()
endfunction()

find_package(Eigen3 3.3 QUIET NO_MODULE)
if(NOT Eigen3_FOUND)
  message(FATAL_ERROR "Eigen3 not found: apt-get install libeigen3-dev")
endif()

find_package(nlohmann_json 3.9 QUIET)
if(NOT nlohmann_json_FOUND)
  message(FATAL_ERROR "nlohmann_json not found: apt-get install nlohmann-json3-dev")
endif()

find_path(UNIDIST_CLI11_INCLUDE CLI/CLI.hpp)
if(NOT UNIDIST_CLI11_INCLUDE)
  message(FATAL_ERROR "CLI11 not found: apt-get install libcli11-dev")
endif()

option(UNIDIST_BULLET_DOUBLE "Use Debian's double-precision Bullet (bullet-float64)" OFF)
if(UNIDIST_BULLET_DOUBLE)
  unidist_require_pc(BULLET "bullet-float64>=3.24" libbullet-dev)
else()
  unidist_require_pc(BULLET "bullet>=3.24" libbullet-dev)
endif()
unidist_require_pc(ODE "ode>=0.16" libode-dev)
# The rasterization target (core/raster: image-space penetration depth, headless pictures) is optional: built
# whenever OSMesa and qhull are there. PNG frames (demos) also need libpng.
pkg_check_modules(OSMESA QUIET IMPORTED_TARGET GLOBAL osmesa)
pkg_check_modules(QHULL QUIET IMPORTED_TARGET GLOBAL qhull_r)
pkg_check_modules(PNG QUIET IMPORTED_TARGET GLOBAL libpng)
if(OSMESA_FOUND AND QHULL_FOUND)
  set(UNIDIST_HAVE_RASTER ON)
else()
  set(UNIDIST_HAVE_RASTER OFF)
  message(STATUS "unidist: core/raster not built (needs libosmesa6-dev and libqhull-dev)")
endif()
# Engine headers are SYSTEM includes so their warnings never trip -Werror.
foreach(_engine BULLET ODE)
  get_target_property(_dirs PkgConfig::${_engine} INTERFACE_INCLUDE_DIRECTORIES)
  if(_dirs)
    set_property(TARGET PkgConfig::${_engine} PROPERTY INTERFACE_SYSTEM_INCLUDE_DIRECTORIES "${_dirs}")
  endif()
endforeach()

# The engines' scalar widths must match the headers we compile against; a mismatch links and then crashes.
include(CheckCXXSourceCompiles)
set(CMAKE_REQUIRED_LIBRARIES PkgConfig::ODE)
check_cxx_source_compiles([[#include <ode/ode.h>
  static_assert(sizeof(dReal) == sizeof(double), "ODE is not double"); int main() {}]] UNIDIST_ODE_DOUBLE)
set(CMAKE_REQUIRED_LIBRARIES PkgConfig::BULLET)
check_cxx_source_compiles([[#include <btBulletCollisionCommon.h>
  int main() { btSphereShape s(1); btVector3 i; s.calculateLocalInertia(1, i); }]] UNIDIST_BULLET_LINKS)
unset(CMAKE_REQUIRED_LIBRARIES)
if(NOT UNIDIST_ODE_DOUBLE OR NOT UNIDIST_BULLET_LINKS)
  message(FATAL_ERROR "engine scalar width mismatch (ODE double: ${UNIDIST_ODE_DOUBLE}, Bullet links: ${UNIDIST_BULLET_LINKS}); "
                      "install libbullet-dev and libode-dev from Debian and do not mix bullet and bullet-float64")
endif()

if(UNIDIST_BUILD_TESTS)
  find_package(GTest 1.10 QUIET)
  if(NOT GTest_FOUND)
    message(FATAL_ERROR "GoogleTest not found: apt-get install libgtest-dev")
  endif()
  include(GoogleTest)
endif()
if(UNIDIST_BUILD_BENCHMARKS)
  find_package(benchmark QUIET)
  if(NOT benchmark_FOUND)
    message(FATAL_ERROR "Google Benchmark not found: apt-get install libbenchmark-dev")
  endif()
  # FCL is the peer for mesh benchmarks: optional.
  pkg_check_modules(FCL QUIET IMPORTED_TARGET GLOBAL fcl)
endif()
