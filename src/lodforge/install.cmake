# `cmake --install build --prefix P`: the lodforge command and its man page, the
# headers under P/include/lodforge/<module>/, the module libraries exported as
# lodforge::<module> plus the umbrella lodforge::lodforge (find_package(lodforge)),
# and lodforge.pc for pkg-config. The paths inside the package are relative to
# it, so the prefix is chosen at install time.
include(CMakePackageConfigHelpers)

set(lodforge_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/lodforge)

install(TARGETS lodforge_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(FILES ${PROJECT_SOURCE_DIR}/docs/lodforge.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)

# apps/ is the command, not the library: its headers stay private.
install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/lodforge
        FILES_MATCHING PATTERN "*.h" PATTERN "apps" EXCLUDE)

install(TARGETS ${lodforge_module_targets} lodforge EXPORT lodforgeTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT lodforgeTargets NAMESPACE lodforge:: DESTINATION ${lodforge_cmake_dir})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/lodforgeConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/lodforgeConfig.cmake
                              INSTALL_DESTINATION ${lodforge_cmake_dir})
# 0.x: a new minor version may break the API.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/lodforgeConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/lodforgeConfig.cmake
              ${PROJECT_BINARY_DIR}/lodforgeConfigVersion.cmake
        DESTINATION ${lodforge_cmake_dir})

# pkg-config: the prefix is found from the .pc file's own folder. Static
# libraries, so Libs lists every module, users before what they use.
set(pc_dir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)
file(RELATIVE_PATH LODFORGE_PC_PREFIX /p/${pc_dir} /p)
string(REGEX REPLACE "/$" "" LODFORGE_PC_PREFIX "${LODFORGE_PC_PREFIX}")
set(LODFORGE_PC_LIBS "")
foreach(m lod mcoctree render gltf vrml97 vrml1 metrics simplify scene mesh core)
  string(APPEND LODFORGE_PC_LIBS " -llodforge_${m}")
endforeach()
configure_file(${PROJECT_SOURCE_DIR}/cmake/lodforge.pc.in ${PROJECT_BINARY_DIR}/lodforge.pc @ONLY)
install(FILES ${PROJECT_BINARY_DIR}/lodforge.pc DESTINATION ${pc_dir})
