# Packages: a Debian package and a tarball (cpack --config build/CPackConfig.cmake, or
# `cmake --build build --target package`). Both install the CLI, the first-party plugins, the SDK
# (headers + CMake package for find_package(Nimbus)), the OCIO config, the scenes and what
# packaging/install.cmake adds (Slurm scripts, man pages, bash completion, copyright): one package holding
# both install components (`runtime`, `sdk`; see the top-level CMakeLists.txt). Per-component packages
# are one switch away (CPACK_ARCHIVE_COMPONENT_INSTALL / CPACK_DEB_COMPONENT_INSTALL ON).
set(CPACK_PACKAGE_NAME nimbus)
set(CPACK_PACKAGE_VENDOR "Nimbus")
set(CPACK_PACKAGE_CONTACT "Nimbus maintainers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Progressive CPU renderer with a one-click caustics solver")
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_GENERATOR "DEB;TGZ")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# Stripped binaries in nimbus_<version>_<arch>.deb and their debug information in a separate
# nimbus-dbgsym_<version>_<arch>.ddeb (install it with dpkg -i for backtraces with file and line): the DEB
# generator splits it off itself, so CPack must not strip first. The tarball keeps it in the binaries.
set(CPACK_STRIP_FILES OFF)
set(CPACK_DEBIAN_DEBUGINFO_PACKAGE ON)
# Only the two components: anything installed without one would be a packaging mistake, not a third one.
set(CPACK_COMPONENTS_ALL runtime sdk)
include(CPack)
cpack_add_component(runtime DISPLAY_NAME "Nimbus renderer"
  DESCRIPTION "nimbus CLI, first-party plugins, OCIO config and example scenes")
cpack_add_component(sdk DISPLAY_NAME "Nimbus plugin SDK"
  DESCRIPTION "C headers, C++ wrapper and CMake package (find_package(Nimbus)) for writing plugins")
