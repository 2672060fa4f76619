# heavytop's install rules (included from the root when HEAVYTOP_INSTALL is ON):
#   include/heavytop/*.hpp, include/heavytop/symbolic/*.hpp   the public headers
#   lib/libheavytop_core.a, lib/libheavytop_symbolic.a        the static libraries
#   lib/cmake/heavytop/                                        find_package(heavytop)
#   lib/pkgconfig/heavytop.pc, heavytop-symbolic.pc            pkg-config
#   bin/heavytop, bin/heavytop-derive                           the command, when built
# Every destination is relative to the prefix given at install time (cmake --install --prefix),
# and the generated files find that prefix from their own location: the tree is relocatable.
include(CMakePackageConfigHelpers)

set(HEAVYTOP_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/heavytop)
set(HEAVYTOP_PKGCONFIG_DIR ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# Headers: the core's, the generated version.hpp, and the symbolic ones.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/include/heavytop
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        COMPONENT heavytop_development FILES_MATCHING PATTERN "*.hpp")
install(FILES ${PROJECT_BINARY_DIR}/include/heavytop/version.hpp
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/heavytop COMPONENT heavytop_development)

# Libraries, one export set each, so that heavytop::core never needs GiNaC.
install(TARGETS heavytop_core EXPORT heavytopCoreTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT heavytop_development)
install(EXPORT heavytopCoreTargets NAMESPACE heavytop:: DESTINATION ${HEAVYTOP_CMAKE_DIR}
        COMPONENT heavytop_development)
if(TARGET heavytop_symbolic)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/symbolic/include/heavytop
          DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
          COMPONENT heavytop_development FILES_MATCHING PATTERN "*.hpp")
  install(TARGETS heavytop_symbolic EXPORT heavytopSymbolicTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT heavytop_development)
  install(EXPORT heavytopSymbolicTargets NAMESPACE heavytop:: DESTINATION ${HEAVYTOP_CMAKE_DIR}
          COMPONENT heavytop_development)
endif()

if(TARGET heavytop)
  install(TARGETS heavytop RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT heavytop_runtime)
endif()
if(TARGET heavytop-derive)  # beside heavytop, which runs it for `heavytop derive`
  install(TARGETS heavytop-derive RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT heavytop_runtime)
endif()

# The CMake package: heavytopConfig.cmake (finds the dependencies, then the targets).
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/heavytopConfig.cmake.in
  ${PROJECT_BINARY_DIR}/heavytopConfig.cmake INSTALL_DESTINATION ${HEAVYTOP_CMAKE_DIR})
# 0.x: a minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/heavytopConfigVersion.cmake
  VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/heavytopConfig.cmake ${PROJECT_BINARY_DIR}/heavytopConfigVersion.cmake
        DESTINATION ${HEAVYTOP_CMAKE_DIR} COMPONENT heavytop_development)

# pkg-config: the prefix is ${pcfiledir} climbed back up from lib/pkgconfig (or whatever
# CMAKE_INSTALL_LIBDIR is); a static library's own dependencies go in Requires and Libs,
# not .private, so that `pkg-config --libs heavytop` links without --static.
file(RELATIVE_PATH HEAVYTOP_PC_TO_PREFIX /prefix/${HEAVYTOP_PKGCONFIG_DIR} /prefix)
string(REGEX REPLACE "/$" "" HEAVYTOP_PC_TO_PREFIX "${HEAVYTOP_PC_TO_PREFIX}")
foreach(dir IN ITEMS LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE "${CMAKE_INSTALL_${dir}}")
    message(WARNING "heavytop: CMAKE_INSTALL_${dir} is absolute; the .pc files will not be relocatable")
    set(HEAVYTOP_PC_${dir} "${CMAKE_INSTALL_${dir}}")
  else()
    set(HEAVYTOP_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
set(pc_files heavytop)
if(TARGET heavytop_symbolic)
  list(APPEND pc_files heavytop-symbolic)
endif()
foreach(pc IN LISTS pc_files)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/${pc}.pc.in ${PROJECT_BINARY_DIR}/${pc}.pc @ONLY)
  install(FILES ${PROJECT_BINARY_DIR}/${pc}.pc DESTINATION ${HEAVYTOP_PKGCONFIG_DIR}
          COMPONENT heavytop_development)
endforeach()
