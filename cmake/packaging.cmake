# The Debian package of the appliance (CPack DEB; `scripts/dev package`, docs/INSTALL.md):
#   /usr/bin/mirror                        the firmware
#   /etc/mirror/mirror.toml                the configuration (a conffile: local edits survive upgrades)
#   /usr/share/mirror/                     assets
#   /lib/systemd/system/mirror.service     the unit (+ mirror-console.service: no blanking)
#   /lib/udev/rules.d/60-mirror-gpio.rules GPIO chips for the gpio group
#   /usr/lib/modules-load.d/mirror.conf    V4L2, media and DRM cores at boot (hot-plug under DevicePolicy)
#   /usr/share/doc/mirror/                 integration-guide.md (docs/INSTALL.md), copyright, changelog.gz
#   /usr/share/man/man1/mirror.1.gz        the man page (help2man from --help)
# The postinst creates the system user `mirror` and the device groups, and enables the unit on
# first install only (deb-systemd-helper; tests/packaging checks the maintainer scripts, and
# lintian the package: tests/packaging/lintian.sh).
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
install(FILES ${CMAKE_CURRENT_LIST_DIR}/debian/copyright DESTINATION share/doc/mirror
        COMPONENT appliance)
# The integrator's guide (an INSTALL file in /usr/share/doc would be upstream build instructions).
install(FILES ${PROJECT_SOURCE_DIR}/docs/INSTALL.md DESTINATION share/doc/mirror
        RENAME integration-guide.md COMPONENT appliance)

# The changelog's newest entry is this release: its version must be the project's, its date dates
# the man page (SOURCE_DATE_EPOCH: the same bytes from every build).
execute_process(COMMAND dpkg-parsechangelog -l ${CMAKE_CURRENT_LIST_DIR}/debian/changelog -S Version
                OUTPUT_VARIABLE changelog_version OUTPUT_STRIP_TRAILING_WHITESPACE)
execute_process(COMMAND dpkg-parsechangelog -l ${CMAKE_CURRENT_LIST_DIR}/debian/changelog -S Timestamp
                OUTPUT_VARIABLE MIRROR_RELEASE_EPOCH OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT changelog_version STREQUAL PROJECT_VERSION)
  message(FATAL_ERROR "cmake/debian/changelog's newest entry is ${changelog_version}, the project is "
                      "${PROJECT_VERSION}: add an entry for this release")
endif()

# Debian policy's documentation: the changelog and the man page, compressed reproducibly (gzip -n).
# The man page is the program's own --help (help2man), so it never drifts from the options.
set(MIRROR_DOC_DIR ${CMAKE_BINARY_DIR}/debian-doc)
add_custom_command(OUTPUT ${MIRROR_DOC_DIR}/changelog.gz
  COMMAND ${CMAKE_COMMAND} -E make_directory ${MIRROR_DOC_DIR}
  COMMAND gzip -9nc ${CMAKE_CURRENT_LIST_DIR}/debian/changelog > ${MIRROR_DOC_DIR}/changelog.gz
  DEPENDS ${CMAKE_CURRENT_LIST_DIR}/debian/changelog VERBATIM)
set(mirror_docs ${MIRROR_DOC_DIR}/changelog.gz)
find_program(HELP2MAN help2man)
if(HELP2MAN)
  add_custom_command(OUTPUT ${MIRROR_DOC_DIR}/mirror.1.gz
    COMMAND ${CMAKE_COMMAND} -E make_directory ${MIRROR_DOC_DIR}
    COMMAND ${CMAKE_COMMAND} -E env SOURCE_DATE_EPOCH=${MIRROR_RELEASE_EPOCH}
            ${HELP2MAN} --no-info --section=1 --name=smart\ mirror\ appliance\ firmware
            --include=${CMAKE_CURRENT_LIST_DIR}/debian/mirror.h2m --output=${MIRROR_DOC_DIR}/mirror.1
            $<TARGET_FILE:mirror>
    COMMAND gzip -9nf ${MIRROR_DOC_DIR}/mirror.1
    DEPENDS mirror ${CMAKE_CURRENT_LIST_DIR}/debian/mirror.h2m VERBATIM)
  list(APPEND mirror_docs ${MIRROR_DOC_DIR}/mirror.1.gz)
  install(FILES ${MIRROR_DOC_DIR}/mirror.1.gz DESTINATION share/man/man1 COMPONENT appliance)
else()
  message(WARNING "help2man not found: the package will have no man page (apt-get install help2man)")
endif()
add_custom_target(mirror_package_docs ALL DEPENDS ${mirror_docs})
install(FILES ${MIRROR_DOC_DIR}/changelog.gz DESTINATION share/doc/mirror COMPONENT appliance)

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
# The extended description (CPack puts the summary before it and a space before each line): lines
# of at most 80 columns.
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION "A camera above a display shows people their mirror image; the firmware tracks
faces and a coloured card and draws overlays on them. Boots straight into the
mirror (systemd unit); a diagnostics console on the serial port.")
set(CPACK_PACKAGE_CONTACT "Smart mirror developers <firmware@smart-mirror.example>")
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
# the Haar cascades, libcamera's IPA modules, the Mesa drivers, useradd (setterm: util-linux is
# essential).
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "opencv-data, libcamera-ipa, libegl-mesa0, libgl1-mesa-dri, passwd, systemd, init-system-helpers (>= 1.52)")
# The binary without its symbol tables (lintian: unstripped-binary-or-object).
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${MIRROR_DEBIAN_DIR}/postinst ${MIRROR_DEBIAN_DIR}/prerm ${MIRROR_DEBIAN_DIR}/postrm
    ${MIRROR_DEBIAN_DIR}/conffiles)
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION TRUE)
include(CPack)
