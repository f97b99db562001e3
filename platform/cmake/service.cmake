# libsystemd for platform::ServiceNotifier (sd_notify, sd_watchdog_enabled). Included from the
# top-level CMakeLists.txt once the platform target exists.
pkg_check_modules(SYSTEMD REQUIRED IMPORTED_TARGET libsystemd)
target_link_libraries(platform PRIVATE PkgConfig::SYSTEMD)
