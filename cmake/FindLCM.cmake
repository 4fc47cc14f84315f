# Debian 12 ships LCM 1.3.1 without a CMake package. Its lcm.pc requires glib's .pc files,
# which the C++ headers do not need, so we find the header and the library directly.
# Defines the imported target LCM::lcm and LCM_GEN_EXECUTABLE.
find_path(LCM_INCLUDE_DIR lcm/lcm-cpp.hpp)
find_library(LCM_LIBRARY lcm)
find_program(LCM_GEN_EXECUTABLE lcm-gen)
find_file(LCM_JAR lcm.jar PATHS /usr/share/java /usr/local/share/java)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(LCM REQUIRED_VARS LCM_LIBRARY LCM_INCLUDE_DIR LCM_GEN_EXECUTABLE)

if(LCM_FOUND AND NOT TARGET LCM::lcm)
  add_library(LCM::lcm UNKNOWN IMPORTED)
  set_target_properties(LCM::lcm PROPERTIES
    IMPORTED_LOCATION "${LCM_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${LCM_INCLUDE_DIR}")
endif()
