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
    # TCG, with the sanitizer build's device tests and the 1 MiB flood: ~3 min on two idle cores,
    # ~6 min on busy ones (the guest is stopped at 480 s: run-hil.sh, HIL_TIMEOUT); the module
    # build (first run only) adds ~20 s.
    TIMEOUT 540
    # The VM takes both cores: nothing else in parallel.
    RUN_SERIAL TRUE)
endif()
