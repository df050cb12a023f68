# Siconos numerics from Debian, found directly (SICONOS_NUMERICS_FOUND, target siconos_numerics).
#
# Debian's libsiconos-numerics-dev (4.4.0, config installed as siconos-4.5.0) ships a
# siconos-config.cmake for the whole Siconos suite: find_package(siconos) stops configuration
# with a fatal error on the missing /usr/bin/siconos, and would set CMAKE_CXX_STANDARD 11 in
# the caller's scope. The numerics library and its headers are found directly instead; they
# include CXSparse's cs.h.
if(TARGET siconos_numerics)
  return()
endif()
find_path(SICONOS_NUMERICS_INCLUDE_DIR FrictionContactProblem.h PATH_SUFFIXES siconos/numerics)
find_path(SICONOS_CONFIG_INCLUDE_DIR SiconosConfig.h PATH_SUFFIXES siconos)
find_path(CXSPARSE_INCLUDE_DIR cs.h PATH_SUFFIXES suitesparse)
find_library(SICONOS_NUMERICS_LIBRARY siconos_numerics)
if(SICONOS_NUMERICS_INCLUDE_DIR AND SICONOS_CONFIG_INCLUDE_DIR AND CXSPARSE_INCLUDE_DIR AND SICONOS_NUMERICS_LIBRARY)
  set(SICONOS_NUMERICS_FOUND TRUE)
  add_library(siconos_numerics INTERFACE IMPORTED)
  target_include_directories(siconos_numerics SYSTEM INTERFACE
    "${SICONOS_NUMERICS_INCLUDE_DIR}" "${SICONOS_CONFIG_INCLUDE_DIR}" "${CXSPARSE_INCLUDE_DIR}")
  target_link_libraries(siconos_numerics INTERFACE "${SICONOS_NUMERICS_LIBRARY}")
else()
  set(SICONOS_NUMERICS_FOUND FALSE)
endif()
