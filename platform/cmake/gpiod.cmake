# libgpiod for the GPIO buttons (GpiodButtonInput). Debian 12 ships 1.6 (libgpiod-dev); the code
# picks the 1.x or 2.x adapter from the header itself (platform/src/gpiod_lines.hpp).
# Included by the top-level CMakeLists.txt after add_subdirectory(platform).
pkg_check_modules(LIBGPIOD REQUIRED IMPORTED_TARGET libgpiod)
target_link_libraries(platform PRIVATE PkgConfig::LIBGPIOD)
