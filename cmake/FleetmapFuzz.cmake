# FLEETMAP_FUZZ: the libFuzzer targets in fuzz/ (docs/fuzzing.md). libFuzzer only guides its
# mutations by what it can see, so every library a target links is built with coverage
# instrumentation (-fsanitize=fuzzer-no-link), not only the target's own file; ASan and UBSan
# turn silent memory and arithmetic errors into crashes. Assertions stay on whatever the build
# type: an assert that outside data can reach is a bug the fuzzer must report, not skip.
if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
  message(FATAL_ERROR "FLEETMAP_FUZZ needs clang (libFuzzer ships with it): configure with "
                      "-DCMAKE_CXX_COMPILER=clang++-14, as ./run_fuzz.sh does")
endif()
if(FLEETMAP_SANITIZE)
  message(FATAL_ERROR "FLEETMAP_FUZZ already builds with ASan and UBSan: "
                      "leave FLEETMAP_SANITIZE off")
endif()
add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=all
                    -fno-omit-frame-pointer -UNDEBUG)
add_link_options(-fsanitize=address,undefined)
