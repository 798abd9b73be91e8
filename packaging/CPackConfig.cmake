# Packages: a Debian package and a tarball (cpack --config build/CPackConfig.cmake, or
# `cmake --build build --target package`). Both install the CLI, the first-party plugins, the SDK
# (headers + CMake package for find_package(Nimbus)), the OCIO config and the scenes.
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
set(CPACK_STRIP_FILES OFF)
include(CPack)
