# CPack DEB settings for headingd_<version>_<arch>.deb. The package's contents are exactly
# the install rules of the project (cmake --install), so the package and a source install
# cannot differ.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME headingd)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "headingd maintainers <maintainers@users.noreply.h-seed-c0998dae.example>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Relative install destinations go under /usr whatever the build's CMAKE_INSTALL_PREFIX
# (so a development tree packs the same layout); absolute ones (/etc/headingd,
# /lib/systemd/system) stay as they are. CPACK_SET_DESTDIR would use the build's prefix.
set(CPACK_SET_DESTDIR OFF)
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Depends: the shared libraries the programs link (dpkg-shlibdeps); systemd-sysusers,
# which postinst runs to create the user; python3, as Debian's Python policy asks of a
# package with public modules (the LCM types in dist-packages).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "systemd-sysusers, python3:any")
# The message types: the C++ headers need LCM's, the jar LCM's jar; lcm-spy and lcm-logger
# come with liblcm-bin; can-utils to look at the bus.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "liblcm-dev, liblcm-java, liblcm-bin, can-utils")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time heading and attitude daemon (IMU over CAN, GPS, LCM)")
# The long description; CPack puts the summary above it as the synopsis, indents each line
# and turns the empty line into " .".
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "headingd estimates the attitude and the true heading of a body-worn Linux
computer from a 9-axis IMU on SocketCAN (frames decoded by a DBC file) and
an NMEA GPS receiver on a serial port, with the World Magnetic Model, and
publishes them over LCM at a fixed rate. It runs as a systemd service
(Type=notify, watchdog) configured by /etc/headingd/headingd.toml.

The package also holds the offline tools (replay, calibration, simulator,
World Magnetic Model), a demo capture, and the LCM message types for C++,
Java (lcm-spy) and Python subscribers.")
# Maintainer scripts (user, systemd) and the conffile list. Strict permissions: 0755
# scripts, 0644 lists, as dpkg-deb and lintian expect.
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
  ${CMAKE_CURRENT_SOURCE_DIR}/deb/conffiles
  ${CMAKE_CURRENT_SOURCE_DIR}/deb/postinst
  ${CMAKE_CURRENT_SOURCE_DIR}/deb/prerm
  ${CMAKE_CURRENT_SOURCE_DIR}/deb/postrm)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
include(CPack)
