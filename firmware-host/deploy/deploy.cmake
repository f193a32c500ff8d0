# firmware-host/deploy/deploy.cmake: `cmake --install` and `cpack -G DEB`
# (firmware-host/deploy/README.md). Included at the end of the top-level
# CMakeLists.txt, after the facectl target and FACECTL_INSTALL_CONFIG_DIR.
#
# The paths are fixed at configure time: the binary compiles in where the
# installed configs are (firmware-host/config/config_location.hpp) and the
# unit names the binary and the runtime file. So choose the prefix with
# -DCMAKE_INSTALL_PREFIX, not with `cmake --install --prefix`. This project's
# default prefix is /usr (below): a system service with its configs in
# /etc/facectl and its unit, sysusers and udev files where systemd and udev
# read a package's, the paths of facectl.service and of the .deb.

set(FACECTL_SYSTEMD_UNIT_DIR "lib/systemd/system" CACHE STRING
    "systemd unit folder, relative to the install prefix")
set(FACECTL_SYSUSERS_DIR "lib/sysusers.d" CACHE STRING
    "sysusers.d folder, relative to the install prefix")
set(FACECTL_UDEV_RULES_DIR "lib/udev/rules.d" CACHE STRING
    "udev rules folder, relative to the install prefix")

set(facectl_deploy_out "${PROJECT_BINARY_DIR}/deploy")
set(FACECTL_UNIT_BINARY "${CMAKE_INSTALL_FULL_BINDIR}/facectl")
configure_file("${CMAKE_CURRENT_LIST_DIR}/facectl.service.in" "${facectl_deploy_out}/facectl.service"
               @ONLY)

install(TARGETS facectl RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
# The whole config/ tree: the runtime file, heads, rigs, expressions, shows, fap/.
install(DIRECTORY "${FACECTL_CONFIG_DIR}/" DESTINATION "${FACECTL_INSTALL_CONFIG_DIR}")
# The operator web console of `facectl serve`, once the source tree has it.
install(DIRECTORY "${FACECTL_CONSOLE_DIR}/" DESTINATION "${CMAKE_INSTALL_DATADIR}/facectl/console"
        OPTIONAL)
install(FILES "${facectl_deploy_out}/facectl.service" DESTINATION "${FACECTL_SYSTEMD_UNIT_DIR}")
install(FILES "${CMAKE_CURRENT_LIST_DIR}/facectl.sysusers" DESTINATION "${FACECTL_SYSUSERS_DIR}"
        RENAME facectl.conf)
install(FILES "${CMAKE_CURRENT_LIST_DIR}/60-facectl.rules" DESTINATION "${FACECTL_UDEV_RULES_DIR}")
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION "${CMAKE_INSTALL_DOCDIR}")
install(FILES "${PROJECT_SOURCE_DIR}/LICENSE" DESTINATION "${CMAKE_INSTALL_DOCDIR}" RENAME copyright)

# ---- cpack -G DEB: the package facectl.
# Every file under /etc that a package ships is a conffile (Debian policy
# 10.7.2): dpkg keeps an administrator's edits on upgrade and asks.
file(GLOB_RECURSE facectl_config_files CONFIGURE_DEPENDS RELATIVE "${FACECTL_CONFIG_DIR}"
     "${FACECTL_CONFIG_DIR}/*")
list(SORT facectl_config_files)
list(TRANSFORM facectl_config_files PREPEND "${FACECTL_INSTALL_CONFIG_DIR}/")
list(JOIN facectl_config_files "\n" facectl_conffiles)
file(CONFIGURE OUTPUT "${facectl_deploy_out}/conffiles" CONTENT "${facectl_conffiles}\n" @ONLY)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME facectl)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "real-time controller for animatronic faces")
set(CPACK_PACKAGE_DESCRIPTION
    "facectl turns facial intent (expressions, shows, MPEG-4 FAP files, a gamepad)
into actuator motion inside a head's safety envelope, at 1 kHz, over CAN and
Modbus. The package holds the program, the default configuration in
${FACECTL_INSTALL_CONFIG_DIR}, the facectl.service unit (installed, not enabled
or started), the facectl system user and udev rules for GPIO, hidraw and
USB-serial devices.")
set(FACECTL_PACKAGE_MAINTAINER
    "facectl maintainers <maintainers@users.noreply.h-seed-f01ad37f.example>" CACHE STRING
    "Maintainer field of the .deb")
set(CPACK_PACKAGE_CONTACT "${FACECTL_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # facectl_VERSION_ARCH.deb
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
# The shared libraries' packages, from dpkg-shlibdeps; systemd for
# systemd-sysusers (postinst) and the unit.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "systemd")
# pocketsphinx-en-us: the models `--format audio_phonemes` recognises phones
# with (docs/INPUTS.md); without them only that format fails, naming it.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "udev, pocketsphinx-en-us")
set(CPACK_STRIP_FILES ON)
# postinst creates the user and reloads udev; it neither enables nor starts
# the service (debian/postinst says why).
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    "${CMAKE_CURRENT_LIST_DIR}/debian/postinst;${CMAKE_CURRENT_LIST_DIR}/debian/prerm;\
${CMAKE_CURRENT_LIST_DIR}/debian/postrm;${facectl_deploy_out}/conffiles")
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
# The package installs where the tree was configured to (the binary and the
# unit name these paths), and a Debian package installs under /usr: cpack
# refuses another prefix (cpack_project_config.cmake) rather than ship a
# package whose binary looks for its configs elsewhere.
set(CPACK_PACKAGING_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")
set(CPACK_FACECTL_INSTALL_PREFIX "${CMAKE_INSTALL_PREFIX}")
set(CPACK_PROJECT_CONFIG_FILE "${CMAKE_CURRENT_LIST_DIR}/cpack_project_config.cmake")
# cpack installs the project into its staging tree through the preinstall
# target, which builds `all` (every test) first unless told not to: with this,
# cpack in a tree where facectl is built only packages. `cmake --install`
# never builds; build facectl before either.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
include(CPack)
