# CMake toolchain file: 64-bit Arm Linux (AArch64) with Debian's cross compiler
# (g++-aarch64-linux-gnu), against Debian's multiarch arm64 packages (libtbb-dev:arm64,
# libspng-dev:arm64, ...: scripts/setup.sh installs them for the arm64 stage of
# scripts/test.sh), whose libraries live in /usr/lib/aarch64-linux-gnu beside the host's.
#
#   cmake -S . -B build-arm64 -G Ninja -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake \
#     -DTESSERA_BUILD_PYTHON=OFF -DTESSERA_BUILD_BENCH=OFF
#   qemu-aarch64 -L / build-arm64/bin/simd_test
#
# The OpenGL runtime (tessera_gl, tessera-glpeer) is left out: no arm64 EGL / GL packages.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)

# Libraries and package files: the arm64 ones only (lib/aarch64-linux-gnu under each prefix),
# never the host's; programs (pkg-config, python3) are the host's.
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE BOTH)
set(CMAKE_FIND_ROOT_PATH /)
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/aarch64-linux-gnu/pkgconfig:/usr/share/pkgconfig)
set(ENV{PKG_CONFIG_PATH} "")
set(CMAKE_DISABLE_FIND_PACKAGE_OpenGL ON)

# Programs the build runs (gtest_discover_tests lists each test binary's tests) go through
# qemu-user. `-L /`: the loader is the multiarch libc6:arm64's /lib/ld-linux-aarch64.so.1, the
# same glibc build as the libc.so.6 it loads from /lib/aarch64-linux-gnu. Not the cross
# toolchain's /usr/aarch64-linux-gnu (its ld.so is another glibc build, and with the multiarch
# libc.so.6 pthread_create hangs).
set(CMAKE_CROSSCOMPILING_EMULATOR qemu-aarch64 -L /)
