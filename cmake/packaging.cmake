# The Debian package of the appliance (CPack DEB; `scripts/dev package`, docs/INSTALL.md):
#   /usr/bin/mirror                        the firmware
#   /etc/mirror/mirror.toml                the configuration (a conffile: local edits survive upgrades)
#   /usr/share/mirror/                     assets
#   /lib/systemd/system/mirror.service     the unit (+ mirror-console.service: no blanking)
#   /lib/udev/rules.d/60-mirror-gpio.rules GPIO chips for the gpio group
#   /usr/lib/modules-load.d/mirror.conf    V4L2, media and DRM cores at boot (hot-plug under DevicePolicy)
#   /usr/share/doc/mirror/INSTALL.md
# The postinst creates the system user `mirror` and the device groups and enables the unit.
# Included from the top-level CMakeLists.txt after the firmware (needs the `mirror` target).

install(TARGETS mirror RUNTIME DESTINATION bin COMPONENT appliance)
install(FILES ${PROJECT_SOURCE_DIR}/config/mirror.toml DESTINATION /etc/mirror COMPONENT appliance)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/ DESTINATION share/mirror COMPONENT appliance)
install(FILES ${PROJECT_SOURCE_DIR}/systemd/mirror.service
              ${PROJECT_SOURCE_DIR}/systemd/mirror-console.service
        DESTINATION /lib/systemd/system COMPONENT appliance)
install(FILES ${PROJECT_SOURCE_DIR}/systemd/mirror-modules.conf
        DESTINATION /usr/lib/modules-load.d RENAME mirror.conf COMPONENT appliance)
install(FILES ${PROJECT_SOURCE_DIR}/systemd/60-mirror-gpio.rules
        DESTINATION /lib/udev/rules.d COMPONENT appliance)
install(FILES ${PROJECT_SOURCE_DIR}/docs/INSTALL.md DESTINATION share/doc/mirror
        COMPONENT appliance)

# dpkg marks nothing as a conffile by itself (debhelper would): list the config.
set(MIRROR_DEBIAN_DIR ${CMAKE_BINARY_DIR}/debian-control)
file(WRITE ${MIRROR_DEBIAN_DIR}/conffiles "/etc/mirror/mirror.toml\n")
foreach(script postinst prerm postrm)
  configure_file(${CMAKE_CURRENT_LIST_DIR}/debian/${script} ${MIRROR_DEBIAN_DIR}/${script}
                 COPYONLY FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ
                 GROUP_EXECUTE WORLD_READ WORLD_EXECUTE)
endforeach()

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME mirror)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Smart mirror appliance firmware")
set(CPACK_PACKAGE_DESCRIPTION
    "A camera above a display shows people their mirror image; the firmware tracks faces and a coloured card and draws overlays on them. Boots straight into the mirror (systemd unit).")
set(CPACK_PACKAGE_CONTACT "Smart mirror developers <mirror@localhost>")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_PACKAGE_DIRECTORY ${CMAKE_BINARY_DIR}/package)
# Only the appliance: not the tests, tools or benchmarks.
set(CPACK_COMPONENTS_ALL appliance)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
# Library dependencies from the binary (dpkg-shlibdeps), plus what is used by path or by command:
# the Haar cascades, libcamera's IPA modules, the Mesa drivers, setterm, useradd.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "opencv-data, libcamera-ipa, libegl-mesa0, libgl1-mesa-dri, util-linux, passwd, systemd")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${MIRROR_DEBIAN_DIR}/postinst ${MIRROR_DEBIAN_DIR}/prerm ${MIRROR_DEBIAN_DIR}/postrm
    ${MIRROR_DEBIAN_DIR}/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
include(CPack)
