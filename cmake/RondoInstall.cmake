# `cmake --install BUILD --prefix PREFIX` and the Debian package (`cpack -G DEB` in BUILD), see
# docs/operations.md. The dashboard is embedded in the binary, so nothing of it is installed.
#   PREFIX/bin/rondo
#   PREFIX/share/rondo/examples/{g4s,office,witham,systemd}/...   (the binary's default deployment)
#   PREFIX/share/doc/rondo/{README.md,api.md,operations.md}
#   PREFIX/lib/systemd/system/rondo.service                       (systemd reads /usr/local/lib too)
include(GNUInstallDirs)
install(TARGETS rondo RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/ DESTINATION ${CMAKE_INSTALL_DATADIR}/rondo/examples)
install(FILES ${PROJECT_SOURCE_DIR}/README.md ${PROJECT_SOURCE_DIR}/docs/api.md ${PROJECT_SOURCE_DIR}/docs/operations.md
        DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(FILES ${PROJECT_SOURCE_DIR}/examples/systemd/rondo.service DESTINATION lib/systemd/system)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME rondo)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "rondo maintainers <rondo@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "long-term task executive for mobile service robots")
set(CPACK_PACKAGE_DESCRIPTION
    "rondo schedules and runs a mobile robot's tasks over months, learns when its paths are \
passable, and serves an HTTP API with a web dashboard (rondo serve).")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # rondo_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)    # Depends: from the libraries the binary links (dpkg-shlibdeps)
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://example.invalid/rondo")
set(CPACK_STRIP_FILES ON)
include(CPack)
