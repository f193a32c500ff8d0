# Read by cpack for each generator (CPACK_PROJECT_CONFIG_FILE, deploy.cmake).
# A .deb installs under /usr, and this tree's binary and unit name the
# configured prefix's paths: refuse to package another.
if(CPACK_GENERATOR STREQUAL "DEB" AND NOT CPACK_FACECTL_INSTALL_PREFIX STREQUAL "/usr")
  message(FATAL_ERROR "facectl: a .deb needs a tree configured with -DCMAKE_INSTALL_PREFIX=/usr "
                      "(this one: ${CPACK_FACECTL_INSTALL_PREFIX}); the binary and facectl.service "
                      "name the configured prefix's paths")
endif()
