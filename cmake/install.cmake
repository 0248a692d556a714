# Installs the library, its headers and a CMake package so that consumers write
#   find_package(fastcorot REQUIRED)  target_link_libraries(app PRIVATE fastcorot::fastcorot)
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS fastcorot EXPORT fastcorotTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
  RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# core/packed.h stays internal: its inline functions return SIMD vectors, whose passing depends on
# the instruction set a consumer compiles for.
install(DIRECTORY include/fastcorot DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} PATTERN "packed.h" EXCLUDE)
install(EXPORT fastcorotTargets NAMESPACE fastcorot::
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/fastcorot)

configure_package_config_file(cmake/fastcorotConfig.cmake.in
  ${PROJECT_BINARY_DIR}/fastcorotConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/fastcorot)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/fastcorotConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/fastcorotConfig.cmake
  ${PROJECT_BINARY_DIR}/fastcorotConfigVersion.cmake
  DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/fastcorot)
