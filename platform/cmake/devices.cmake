# Real capture and display devices of platform/ (libcamera, V4L2 + libjpeg-turbo, DRM/KMS + GBM).
# Included by the top-level CMakeLists.txt after add_subdirectory(platform).
#
# libcamera_source.cpp, drm_display.cpp and window_display.cpp compile only with
# MIRROR_WITH_LIBCAMERA / MIRROR_WITH_DRM / MIRROR_WITH_X11 (their headers need the include paths
# this file adds), so the platform library builds without this file too; v4l2_source.cpp and
# mjpeg_decoder.cpp need only the kernel headers and jpeglib.h (linked here).
pkg_check_modules(LIBCAMERA REQUIRED IMPORTED_TARGET libcamera)
pkg_check_modules(LIBDRM REQUIRED IMPORTED_TARGET libdrm)
pkg_check_modules(GBM REQUIRED IMPORTED_TARGET gbm)
pkg_check_modules(LIBJPEG REQUIRED IMPORTED_TARGET libjpeg)

target_compile_definitions(platform PRIVATE MIRROR_WITH_LIBCAMERA=1 MIRROR_WITH_DRM=1)
target_link_libraries(platform PRIVATE PkgConfig::LIBCAMERA PkgConfig::LIBDRM PkgConfig::GBM
                      PkgConfig::LIBJPEG)

# The development window (X11; XWayland on Wayland desktops).
pkg_check_modules(X11 REQUIRED IMPORTED_TARGET x11)
target_compile_definitions(platform PRIVATE MIRROR_WITH_X11=1)
target_link_libraries(platform PRIVATE PkgConfig::X11)
