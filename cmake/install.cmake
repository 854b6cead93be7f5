# `cmake --install BUILD [--prefix DIR]`: the layers' static libraries, their headers under
# include/skyband/<layer>/, the umbrella header include/skyband/skyband.h, the skyband
# executable, and a package config so that a project finds the library with
#   find_package(skyband REQUIRED)  and links  skyband::skyband  (or one layer, skyband::geometry …).
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS skyband_geometry skyband_lighting skyband_render skyband_io skyband_all
        EXPORT skybandTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS skyband RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
foreach(layer geometry lighting render io)
  install(DIRECTORY ${CMAKE_SOURCE_DIR}/${layer}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/skyband/${layer}
          FILES_MATCHING PATTERN "*.h")
endforeach()
install(FILES ${CMAKE_SOURCE_DIR}/include/skyband/skyband.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/skyband)

set(SKYBAND_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/skyband)
install(EXPORT skybandTargets NAMESPACE skyband:: DESTINATION ${SKYBAND_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/skybandConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/skybandConfig.cmake INSTALL_DESTINATION ${SKYBAND_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/skybandConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/skybandConfig.cmake ${CMAKE_BINARY_DIR}/skybandConfigVersion.cmake
        DESTINATION ${SKYBAND_CMAKE_DIR})
install(FILES ${CMAKE_SOURCE_DIR}/LICENSE DESTINATION ${CMAKE_INSTALL_DATADIR}/doc/skyband)
