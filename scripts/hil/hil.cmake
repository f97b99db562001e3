# The end-to-end test on emulated hardware (scripts/hil/README.md): label "hil", skipped (exit 77,
# with the reason printed) where qemu, the kernel image/headers or linux-source are missing.
# Included from the top-level CMakeLists.txt after the firmware (needs the `mirror` target).
# Not in sanitizer builds: the Release test runs the sanitizer build's device tests in the
# machine (check asan_devices) when build-asan/ exists; a whole sanitized service under TCG would
# be ten times slower.
if(MIRROR_BUILD_TESTS AND CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64" AND NOT CMAKE_CROSSCOMPILING
   AND TARGET mirror
   AND NOT MIRROR_SANITIZE)
  add_test(NAME hil.emulated_machine
    COMMAND ${CMAKE_CURRENT_LIST_DIR}/run-hil.sh ${CMAKE_BINARY_DIR}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(hil.emulated_machine PROPERTIES
    LABELS hil
    SKIP_RETURN_CODE 77
    # Boot, module loads, the package, the service on the real devices and the fault runs under
    # TCG, with the sanitizer build's device tests and the serial flood: ~3 min on two idle
    # cores, several times that on a slow or busy host. run-hil.sh stretches its own limit by the
    # guest's calibration (400 s at the reference speed, at most x4, plus 300 s for the boot and
    # the calibration: 1900 s); this is only the backstop above it. The module build (first run
    # only) adds ~20 s.
    TIMEOUT 2000
    # The VM takes both cores: no other test of this ctest run beside it (scripts/dev test runs
    # this label in a ctest of its own, beside the other phases).
    RUN_SERIAL TRUE)
  # The appliance booted without camera and panel, then both plugged in (README: HIL_SCENARIO).
  add_test(NAME hil.boot_without_devices
    COMMAND ${CMAKE_CURRENT_LIST_DIR}/run-hil.sh ${CMAKE_BINARY_DIR}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  set_tests_properties(hil.boot_without_devices PROPERTIES
    LABELS hil
    SKIP_RETURN_CODE 77
    ENVIRONMENT HIL_SCENARIO=hotplug
    TIMEOUT 2000
    RUN_SERIAL TRUE)
endif()
