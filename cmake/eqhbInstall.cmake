# Install rules: libraries exported as eqhb::<name>, headers under include/eqhb/,
# eqhbConfig.cmake + version file for find_package(eqhb), and eqhb.pc for pkg-config.
include(CMakePackageConfigHelpers)

set(EQHB_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/eqhb)
get_property(eqhb_adapters GLOBAL PROPERTY EQHB_LIBRARIES)
get_property(EQHB_BACKENDS GLOBAL PROPERTY EQHB_BACKENDS)

install(TARGETS eqhb_core eqhb_app ${eqhb_adapters} EXPORT eqhbTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(DIRECTORY ${PROJECT_SOURCE_DIR}/lib/eqhb DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
  FILES_MATCHING PATTERN "*.h")
install(FILES ${PROJECT_BINARY_DIR}/lib/generated/eqhb/version.h
  DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/eqhb)
# Only the adapters that were built have their headers installed.
foreach(target ${eqhb_adapters})
  get_target_property(headers ${target} EQHB_HEADERS)
  get_target_property(folder ${target} EQHB_HEADER_FOLDER)
  install(FILES ${headers} DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${folder})
endforeach()

install(EXPORT eqhbTargets NAMESPACE eqhb:: DESTINATION ${EQHB_CMAKE_DIR})
if(BUILD_SHARED_LIBS)
  set(EQHB_SHARED ON)
else()
  set(EQHB_SHARED OFF)
endif()
configure_package_config_file(cmake/eqhbConfig.cmake.in
  ${PROJECT_BINARY_DIR}/eqhbConfig.cmake INSTALL_DESTINATION ${EQHB_CMAKE_DIR})
# 0.x: a minor version may break the interface.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/eqhbConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/eqhbConfig.cmake ${PROJECT_BINARY_DIR}/eqhbConfigVersion.cmake
  DESTINATION ${EQHB_CMAKE_DIR})

# pkg-config: static archives carry their dependencies into every link, so
# they are public requirements then; shared libraries keep them private.
set(EQHB_PC_LIBS "-leqhb_app -leqhb_solvers")
set(EQHB_PC_REQUIRES_DEPS "fftw3")
set(EQHB_PC_LIBS_DEPS " -lumfpack -lamd -lsuitesparseconfig")  # SuiteSparse has no .pc file on Debian 12
foreach(backend ${EQHB_BACKENDS})
  string(APPEND EQHB_PC_LIBS " -leqhb_${backend}")
  if(backend STREQUAL "ceres")
    string(APPEND EQHB_PC_LIBS_DEPS " -lceres")  # Debian's libceres.so brings its own dependencies
  else()
    string(APPEND EQHB_PC_REQUIRES_DEPS " ${backend}")
  endif()
endforeach()
string(REPLACE "minpack" "cminpack" EQHB_PC_REQUIRES_DEPS "${EQHB_PC_REQUIRES_DEPS}")
string(APPEND EQHB_PC_LIBS " -leqhb_dogleg -leqhb_core")
if(EQHB_SHARED)
  set(EQHB_PC_REQUIRES "eigen3")
  set(EQHB_PC_REQUIRES_PRIVATE "${EQHB_PC_REQUIRES_DEPS}")
  set(EQHB_PC_LIBS_PRIVATE "${EQHB_PC_LIBS_DEPS}")
else()
  set(EQHB_PC_REQUIRES "eigen3 ${EQHB_PC_REQUIRES_DEPS}")
  set(EQHB_PC_REQUIRES_PRIVATE "")
  string(APPEND EQHB_PC_LIBS "${EQHB_PC_LIBS_DEPS}")
  set(EQHB_PC_LIBS_PRIVATE "")
endif()
# Relocatable: the prefix is found from the .pc file's own folder.
file(RELATIVE_PATH EQHB_PC_PREFIX_FROM_PCDIR
  /prefix/${CMAKE_INSTALL_LIBDIR}/pkgconfig /prefix)
string(REGEX REPLACE "/$" "" EQHB_PC_PREFIX_FROM_PCDIR "${EQHB_PC_PREFIX_FROM_PCDIR}")
configure_file(cmake/eqhb.pc.in ${PROJECT_BINARY_DIR}/eqhb.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/eqhb.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
