# The libraries of platform/'s real capture and display devices (libcamera, V4L2 +
# libjpeg-turbo, DRM/KMS + GBM, X11), all required. Included by the top-level CMakeLists.txt after
# add_subdirectory(platform).
pkg_check_modules(LIBCAMERA REQUIRED IMPORTED_TARGET libcamera)
pkg_check_modules(LIBDRM REQUIRED IMPORTED_TARGET libdrm)
pkg_check_modules(GBM REQUIRED IMPORTED_TARGET gbm)
pkg_check_modules(LIBJPEG REQUIRED IMPORTED_TARGET libjpeg)

target_link_libraries(platform PRIVATE PkgConfig::LIBCAMERA PkgConfig::LIBDRM PkgConfig::GBM
                      PkgConfig::LIBJPEG)

# The development window (X11; XWayland on Wayland desktops).
pkg_check_modules(X11 REQUIRED IMPORTED_TARGET x11)
target_link_libraries(platform PRIVATE PkgConfig::X11)
