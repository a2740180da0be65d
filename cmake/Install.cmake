# A relocatable CMake package: find_package(trackphys CONFIG) + trackphys::trackphys.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(TRACKPHYS_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/trackphys)

install(TARGETS trackphys trackphys_options EXPORT trackphysTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/trackphys DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT trackphysTargets NAMESPACE trackphys:: DESTINATION ${TRACKPHYS_CMAKE_DIR})

configure_package_config_file(cmake/trackphysConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/trackphysConfig.cmake
  INSTALL_DESTINATION ${TRACKPHYS_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/trackphysConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/trackphysConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/trackphysConfigVersion.cmake
        DESTINATION ${TRACKPHYS_CMAKE_DIR})

if(TARGET trackphys_app)
  install(TARGETS trackphys_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
endif()
