# Cross-compiling for aarch64 with Debian's crossbuild-essential-arm64 (scripts/arm_build.sh).
# FLEETMAP_ARM_SYSROOT: the arm64 -dev packages unpacked with dpkg -x (libraries and headers);
# the C library and the compiler's own files come from /usr/aarch64-linux-gnu.
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
list(APPEND CMAKE_TRY_COMPILE_PLATFORM_VARIABLES FLEETMAP_ARM_SYSROOT)

set(CMAKE_FIND_ROOT_PATH "${FLEETMAP_ARM_SYSROOT}" /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)  # lcm-gen and the like run on the host
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# Headers in the sysroot (with its multiarch folder), and the libraries' own dependencies
# (glib for liblcm, BLAS/LAPACK for OpenCV) found at link time.
set(fleetmap_arm_inc "${FLEETMAP_ARM_SYSROOT}/usr/include")
set(fleetmap_arm_lib "${FLEETMAP_ARM_SYSROOT}/usr/lib/aarch64-linux-gnu")
set(CMAKE_CXX_FLAGS_INIT "-isystem ${fleetmap_arm_inc} -isystem ${fleetmap_arm_inc}/aarch64-linux-gnu")
set(CMAKE_C_FLAGS_INIT "${CMAKE_CXX_FLAGS_INIT}")
set(CMAKE_EXE_LINKER_FLAGS_INIT
    "-Wl,-rpath-link,${fleetmap_arm_lib} -Wl,-rpath-link,${fleetmap_arm_lib}/blas -Wl,-rpath-link,${fleetmap_arm_lib}/lapack -Wl,-rpath-link,${FLEETMAP_ARM_SYSROOT}/lib/aarch64-linux-gnu")
