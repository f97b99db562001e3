# Cross build for 64-bit ARM (Raspberry Pi 3/4/5 class boards, Debian arm64) with Debian's
# cross compiler (g++-aarch64-linux-gnu). Tests run under qemu user emulation
# (qemu-user-static); binfmt does not need to be registered because CMake and ctest call the
# emulator explicitly. See docs/ARM.md.
#
#   cmake -S . -B build-arm64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64.cmake \
#         -DMIRROR_VISION_ONLY=ON -DCMAKE_BUILD_TYPE=Release

set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)

set(MIRROR_CROSS_TRIPLE aarch64-linux-gnu)
set(CMAKE_C_COMPILER ${MIRROR_CROSS_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${MIRROR_CROSS_TRIPLE}-g++)

# Debian installs the arm64 C/C++ runtime (libc6-dev-arm64-cross, libstdc++-dev-arm64-cross)
# under this prefix; libraries and packages are looked up there only, programs on the host.
set(MIRROR_CROSS_SYSROOT /usr/${MIRROR_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH ${MIRROR_CROSS_SYSROOT})
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Eigen is header-only, so the host's copy (libeigen3-dev) serves every architecture.
if(NOT DEFINED Eigen3_DIR AND EXISTS /usr/share/eigen3/cmake/Eigen3Config.cmake)
  set(Eigen3_DIR /usr/share/eigen3/cmake)
endif()

# ctest (and gtest_discover_tests at build time) run the arm64 binaries through qemu; -L makes
# qemu load the arm64 dynamic loader and libraries from the cross prefix.
find_program(MIRROR_QEMU_AARCH64 NAMES qemu-aarch64-static qemu-aarch64)
if(MIRROR_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${MIRROR_QEMU_AARCH64} -L ${MIRROR_CROSS_SYSROOT})
else()
  message(WARNING "qemu-aarch64-static not found: the arm64 tests cannot run on this machine "
                  "(apt-get install qemu-user-static, or configure with -DMIRROR_BUILD_TESTS=OFF)")
endif()
