# The end-to-end test on emulated hardware (scripts/hil/README.md): label "hil", skipped (exit 77,
# with the reason printed) where qemu, the kernel image/headers or linux-source are missing.
# Included from the top-level CMakeLists.txt after the firmware (needs the `mirror` target).
# Not in sanitizer builds: the same machine, ten times slower, proves nothing more.
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
    # TCG: ~4.5 min on two busy cores (the guest is stopped at 330 s: run-hil.sh, HIL_TIMEOUT);
    # the module build (first run only) adds ~20 s.
    TIMEOUT 380
    # The VM takes both cores: nothing else in parallel.
    RUN_SERIAL TRUE)
endif()
