# Debian packages (CPack, one package per component; ./run_package.sh, docs/deployment.md):
#   fleetmap-common          the system user, /var/lib/fleetmap, the multicast route unit and
#                            the receive-buffer sysctl both processes need (one owner: dpkg
#                            refuses two packages that ship the same file)
#   fleetmap-agent           fleetmap-agent, fleetmap-agent@.service, /etc/fleetmap/agent-example.yaml
#   fleetmap-aggregator      fleetmap-aggregator, fleetmap-mapctl, fleetmap-keygen (the fleet key,
#                            copied to every vehicle), fleetmap-record (the LCM log recorder),
#                            fleetmap-aggregator.service, /etc/fleetmap/aggregator.{yaml,env}
#   fleetmap-tools           simulator, world generator, evaluation, world suite, scanner
#                            emulator, CAN log
#                            writer, maptool, CARMEN evaluation, sample publisher, the LAN
#                            experiment; the worlds
#   fleetmap-lcmtypes-java   the lcm-spy type jar and fleetmap-spy
# Depends: dpkg-shlibdeps reads the binaries (CPACK_DEBIAN_PACKAGE_SHLIBDEPS), plus what the
# scripts call. Files under /etc are conffiles: an operator's edits survive upgrades.
set(fleetmap_pkg_dir "${PROJECT_SOURCE_DIR}/packaging")
# Packaging builds only what it ships (target fleetmap_packaged), not the tests and benchmarks.
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)
set(fleetmap_packaged_targets fleetmap-agent fleetmap-aggregator fleetmap-mapctl fleetmap-keygen fleetmap-record fleetmap-sim
    fleetmap-eval fleetmap-maptool fleetmap-sick-emulator fleetmap-sim-candump
    fleetmap-carmen-eval fleetmap-publish-samples fleetmap-lan-tool fleetmap-worldgen fleetmap-suite
    fleetmap-locate-eval)
add_custom_target(fleetmap_packaged)
add_dependencies(fleetmap_packaged ${fleetmap_packaged_targets})
if(TARGET fleetmap_lcmtypes_jar)
  add_dependencies(fleetmap_packaged fleetmap_lcmtypes_jar)
endif()
set(fleetmap_unit_dir "/lib/systemd/system")  # Debian 12 packages ship units here

# fleetmap-common
install(FILES "${fleetmap_pkg_dir}/systemd/fleetmap-multicast.service"
        DESTINATION "${fleetmap_unit_dir}" COMPONENT common)
install(FILES "${fleetmap_pkg_dir}/etc/60-fleetmap.conf" DESTINATION lib/sysctl.d COMPONENT common)
install(PROGRAMS "${fleetmap_pkg_dir}/lib/fleetmap-multicast-setup" DESTINATION lib/fleetmap
        COMPONENT common)
install(FILES "${fleetmap_pkg_dir}/etc/multicast.env" DESTINATION /etc/fleetmap COMPONENT common)
install(FILES "${fleetmap_pkg_dir}/debian/common/lintian-overrides"
        DESTINATION share/lintian/overrides RENAME fleetmap-common COMPONENT common)
install(FILES "${PROJECT_SOURCE_DIR}/docs/operations.md" "${PROJECT_SOURCE_DIR}/docs/deployment.md"
        DESTINATION share/doc/fleetmap-common COMPONENT common)

# fleetmap-agent
install(TARGETS fleetmap-agent RUNTIME DESTINATION bin COMPONENT agent)
install(FILES "${fleetmap_pkg_dir}/systemd/fleetmap-agent@.service"
        DESTINATION "${fleetmap_unit_dir}" COMPONENT agent)
install(FILES "${fleetmap_pkg_dir}/etc/agent-example.yaml" DESTINATION /etc/fleetmap
        COMPONENT agent)

# fleetmap-aggregator
install(TARGETS fleetmap-aggregator fleetmap-mapctl fleetmap-keygen fleetmap-record RUNTIME DESTINATION bin
        COMPONENT aggregator)
install(FILES "${fleetmap_pkg_dir}/systemd/fleetmap-aggregator.service"
        DESTINATION "${fleetmap_unit_dir}" COMPONENT aggregator)
install(FILES "${fleetmap_pkg_dir}/etc/aggregator.yaml" "${fleetmap_pkg_dir}/etc/aggregator.env"
        DESTINATION /etc/fleetmap COMPONENT aggregator)

# fleetmap-tools: the LAN experiment finds its lib/ and the worlds beside it, as in the
# source tree (/usr/share/fleetmap/ops/lan, .../sim/worlds), and the programs through --bin /usr/bin.
install(TARGETS fleetmap-sim fleetmap-eval fleetmap-maptool fleetmap-sick-emulator
                fleetmap-sim-candump fleetmap-carmen-eval fleetmap-publish-samples fleetmap-lan-tool
                fleetmap-worldgen fleetmap-suite fleetmap-locate-eval
        RUNTIME DESTINATION bin COMPONENT tools)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/sim/worlds" DESTINATION share/fleetmap/sim
        COMPONENT tools)
install(PROGRAMS "${PROJECT_SOURCE_DIR}/ops/lan/fleetmap-lan-experiment"
        DESTINATION share/fleetmap/ops/lan COMPONENT tools)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/ops/lan/lib" DESTINATION share/fleetmap/ops/lan
        COMPONENT tools)
install(FILES "${PROJECT_SOURCE_DIR}/scripts/lib/fleet_launch.sh"
        DESTINATION share/fleetmap/scripts/lib COMPONENT tools)
configure_file("${fleetmap_pkg_dir}/bin/fleetmap-lan-experiment"
               "${PROJECT_BINARY_DIR}/packaging/fleetmap-lan-experiment" @ONLY)
install(PROGRAMS "${PROJECT_BINARY_DIR}/packaging/fleetmap-lan-experiment" DESTINATION bin
        COMPONENT tools)

# fleetmap-lcmtypes-java
set(fleetmap_components common agent aggregator tools)
if(TARGET fleetmap_lcmtypes_jar)
  # The Java policy's names: the versioned jar, and the unversioned name as a link to it.
  install(FILES "${PROJECT_BINARY_DIR}/lcmtypes/fleetmap-lcmtypes.jar" DESTINATION share/java
          RENAME "fleetmap-lcmtypes-${PROJECT_VERSION}.jar" COMPONENT java)
  file(CREATE_LINK "fleetmap-lcmtypes-${PROJECT_VERSION}.jar"
       "${PROJECT_BINARY_DIR}/packaging/fleetmap-lcmtypes.jar" SYMBOLIC)
  install(FILES "${PROJECT_BINARY_DIR}/packaging/fleetmap-lcmtypes.jar" DESTINATION share/java
          COMPONENT java)
  # The source tree's launcher, its version filled in; its helper where it looks when installed.
  configure_file("${PROJECT_SOURCE_DIR}/ops/spy/fleetmap-spy"
                 "${PROJECT_BINARY_DIR}/packaging/fleetmap-spy" @ONLY)
  install(PROGRAMS "${PROJECT_BINARY_DIR}/packaging/fleetmap-spy" DESTINATION bin COMPONENT java)
  install(FILES "${PROJECT_SOURCE_DIR}/ops/spy/lcm_java_env.sh"
          DESTINATION share/fleetmap/ops/spy COMPONENT java)
  list(APPEND fleetmap_components java)
endif()

# Every package's copyright and changelog (Debian policy 12.5, 12.7; a native package's
# changelog is changelog.gz, compressed with gzip -9n so that it carries no timestamp).
set(fleetmap_doc_dir "${PROJECT_BINARY_DIR}/packaging/doc")
configure_file("${fleetmap_pkg_dir}/debian/changelog.in" "${fleetmap_doc_dir}/changelog" @ONLY)
file(REMOVE "${fleetmap_doc_dir}/changelog.gz")
execute_process(COMMAND gzip -9nf "${fleetmap_doc_dir}/changelog" RESULT_VARIABLE gzip_rc)
if(NOT gzip_rc EQUAL 0)
  message(FATAL_ERROR "gzip of the packages' changelog failed")
endif()
function(fleetmap_package_docs component package)
  install(FILES "${fleetmap_pkg_dir}/debian/copyright" "${fleetmap_doc_dir}/changelog.gz"
          DESTINATION "share/doc/${package}" COMPONENT ${component})
endfunction()
fleetmap_package_docs(common fleetmap-common)
fleetmap_package_docs(agent fleetmap-agent)
fleetmap_package_docs(aggregator fleetmap-aggregator)
fleetmap_package_docs(tools fleetmap-tools)
if(TARGET fleetmap_lcmtypes_jar)
  fleetmap_package_docs(java fleetmap-lcmtypes-java)
endif()

# A manual page per program, from its --help by help2man at build time (not when cross-
# compiling: the programs do not run on the build host; nor in sanitizer and fuzzing
# builds, which are not what ships and whose programs may report at exit).
find_program(FLEETMAP_HELP2MAN help2man)
set(fleetmap_man_dir "${PROJECT_BINARY_DIR}/packaging/man")
add_custom_target(fleetmap_man_pages ALL)
add_dependencies(fleetmap_packaged fleetmap_man_pages)
# fleetmap_man_page(COMPONENT NAME "what it is" COMMAND [VERSION]): COMMAND answers --help
# (and --version, unless VERSION is given).
function(fleetmap_man_page component name summary command)
  if(CMAKE_CROSSCOMPILING OR FLEETMAP_SANITIZE OR FLEETMAP_FUZZ)
    return()
  endif()
  if(NOT FLEETMAP_HELP2MAN)
    message(WARNING "help2man not found (scripts/install_deps.sh): no manual page for ${name}")
    return()
  endif()
  set(version_args "")
  if(ARGN)
    set(version_args "--version-string=${ARGN}")
  endif()
  set(page "${fleetmap_man_dir}/${name}.1.gz")
  add_custom_command(
    OUTPUT "${page}"
    COMMAND "${CMAKE_COMMAND}" -E make_directory "${fleetmap_man_dir}"
    COMMAND sh -c "\"$0\" --no-info --no-discard-stderr --name=\"$1\" $2 \"$3\" | gzip -9n > \"$4\""
            "${FLEETMAP_HELP2MAN}" "${summary}" "${version_args}" "${command}" "${page}"
    DEPENDS "${command}"
    COMMENT "help2man ${name}.1"
    VERBATIM)
  add_custom_target(fleetmap_man_${name} DEPENDS "${page}")
  add_dependencies(fleetmap_man_pages fleetmap_man_${name})
  install(FILES "${page}" DESTINATION share/man/man1 COMPONENT ${component})
endfunction()
function(fleetmap_program_man_page component target summary)
  fleetmap_man_page(${component} ${target} "${summary}" "$<TARGET_FILE:${target}>")
  if(TARGET fleetmap_man_${target})
    add_dependencies(fleetmap_man_${target} ${target})
  endif()
endfunction()
fleetmap_program_man_page(agent fleetmap-agent "fleetmap vehicle agent")
fleetmap_program_man_page(aggregator fleetmap-aggregator "merge the fleet's temporary maps into the current map")
fleetmap_program_man_page(aggregator fleetmap-mapctl "export, list, roll back and edit the fleet map's history")
fleetmap_program_man_page(aggregator fleetmap-keygen "write a new fleet key")
fleetmap_program_man_page(aggregator fleetmap-record "record LCM channels to a log file")
fleetmap_program_man_page(tools fleetmap-sim "simulate a warehouse and its vehicles over LCM")
fleetmap_program_man_page(tools fleetmap-eval "evaluate map updates against the simulation's truth")
fleetmap_program_man_page(tools fleetmap-maptool "convert, compare and draw occupancy maps")
fleetmap_program_man_page(tools fleetmap-sick-emulator "emulate a SICK laser scanner on a TCP port")
fleetmap_program_man_page(tools fleetmap-sim-candump "write a simulated vehicle's odometry as a CAN log")
fleetmap_program_man_page(tools fleetmap-carmen-eval "evaluate the scan matcher on a CARMEN log")
fleetmap_program_man_page(tools fleetmap-publish-samples "publish a sample of every fleetmap LCM type")
fleetmap_program_man_page(tools fleetmap-lan-tool "traffic and timing helpers of the LAN experiment")
fleetmap_program_man_page(tools fleetmap-worldgen "generate buildings and scenarios for the world suite")
fleetmap_program_man_page(tools fleetmap-suite "run the world suite")
fleetmap_program_man_page(tools fleetmap-locate-eval "measure global localization against the simulation's truth")
fleetmap_man_page(tools fleetmap-lan-experiment "bandwidth experiments on a LAN of network namespaces"
                  "${PROJECT_SOURCE_DIR}/ops/lan/fleetmap-lan-experiment" "${PROJECT_VERSION}")
if(TARGET fleetmap_lcmtypes_jar)
  fleetmap_man_page(java fleetmap-spy "lcm-spy with fleetmap's message types"
                    "${PROJECT_BINARY_DIR}/packaging/fleetmap-spy")
endif()

# Maintainer scripts and conffiles, per package.
function(fleetmap_control_files component)
  set(dir "${PROJECT_BINARY_DIR}/packaging/control/${component}")
  file(MAKE_DIRECTORY "${dir}")
  set(files "")
  foreach(script postinst postrm prerm)
    if(EXISTS "${fleetmap_pkg_dir}/debian/${component}/${script}")
      # Copied when CMake configures: an edited script must configure again.
      set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS
                                             "${fleetmap_pkg_dir}/debian/${component}/${script}")
      file(COPY "${fleetmap_pkg_dir}/debian/${component}/${script}" DESTINATION "${dir}"
           FILE_PERMISSIONS OWNER_READ OWNER_WRITE OWNER_EXECUTE GROUP_READ GROUP_EXECUTE
                            WORLD_READ WORLD_EXECUTE)
      list(APPEND files "${dir}/${script}")
    endif()
  endforeach()
  if(ARGN)
    list(JOIN ARGN "\n" conffiles)
    file(WRITE "${dir}/conffiles" "${conffiles}\n")
    list(APPEND files "${dir}/conffiles")
  endif()
  string(TOUPPER "${component}" upper)
  set(CPACK_DEBIAN_${upper}_PACKAGE_CONTROL_EXTRA "${files}" PARENT_SCOPE)
endfunction()
fleetmap_control_files(common /etc/fleetmap/multicast.env)
fleetmap_control_files(agent /etc/fleetmap/agent-example.yaml)
fleetmap_control_files(aggregator /etc/fleetmap/aggregator.yaml /etc/fleetmap/aggregator.env)
fleetmap_control_files(tools)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME fleetmap)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_CONTACT "fleetmap developers <fleetmap@example.invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Dynamic warehouse map updates for a vehicle fleet")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_STRIP_FILES TRUE)
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_ALL ${fleetmap_components})
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION misc)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS OFF)
set(fleetmap_common_dep "fleetmap-common (= ${PROJECT_VERSION})")

set(CPACK_DEBIAN_COMMON_PACKAGE_NAME fleetmap-common)
set(CPACK_DEBIAN_COMMON_PACKAGE_ARCHITECTURE all)
set(CPACK_DEBIAN_COMMON_PACKAGE_SHLIBDEPS OFF)
set(CPACK_DEBIAN_COMMON_PACKAGE_DEPENDS "adduser, iproute2, procps")
set(CPACK_DEBIAN_COMMON_DESCRIPTION
    "fleetmap: system user, data folder, LCM multicast route and receive buffer\n The fleetmap user, /var/lib/fleetmap, fleetmap-multicast.service (a route for\n 224.0.0.0/4) and the net.core.rmem_max setting that LCM's 8 MiB receive\n buffers need.")

set(CPACK_DEBIAN_AGENT_PACKAGE_NAME fleetmap-agent)
set(CPACK_DEBIAN_AGENT_PACKAGE_DEPENDS "${fleetmap_common_dep}")
set(CPACK_DEBIAN_AGENT_PACKAGE_SUGGESTS "can-utils, liblcm-bin")
set(CPACK_DEBIAN_AGENT_DESCRIPTION
    "fleetmap vehicle agent\n Runs on every vehicle: localizes on the current map, detects where the laser\n no longer agrees with it, maps that place and sends it to the aggregator over\n LCM. One systemd instance per vehicle: fleetmap-agent@ID.service.")

set(CPACK_DEBIAN_AGGREGATOR_PACKAGE_NAME fleetmap-aggregator)
set(CPACK_DEBIAN_AGGREGATOR_PACKAGE_DEPENDS "${fleetmap_common_dep}")
set(CPACK_DEBIAN_AGGREGATOR_PACKAGE_SUGGESTS "liblcm-bin")
set(CPACK_DEBIAN_AGGREGATOR_DESCRIPTION
    "fleetmap aggregator and fleetmap-mapctl\n Merges the vehicles' temporary maps into the versioned current map and sends\n every change back; fleetmap-mapctl exports, lists, rolls back and edits its\n history.")

set(CPACK_DEBIAN_TOOLS_PACKAGE_NAME fleetmap-tools)
set(CPACK_DEBIAN_TOOLS_PACKAGE_RECOMMENDS "liblcm-bin, iproute2, gnuplot-nox")
set(CPACK_DEBIAN_TOOLS_DESCRIPTION
    "fleetmap simulator, evaluation and test tools\n The warehouse simulator, the evaluation against ground truth, the SICK scanner\n emulator, the CAN log writer, maptool, the CARMEN evaluation and the LAN\n experiment.")

set(CPACK_DEBIAN_JAVA_PACKAGE_NAME fleetmap-lcmtypes-java)
set(CPACK_DEBIAN_JAVA_PACKAGE_ARCHITECTURE all)
set(CPACK_DEBIAN_JAVA_PACKAGE_SHLIBDEPS OFF)
set(CPACK_DEBIAN_JAVA_PACKAGE_DEPENDS "liblcm-java, liblcm-bin, default-jre-headless | java-runtime-headless")
set(CPACK_DEBIAN_JAVA_PACKAGE_RECOMMENDS "libjchart2d-java")
set(CPACK_DEBIAN_JAVA_DESCRIPTION
    "fleetmap LCM message types for lcm-spy\n fleetmap-lcmtypes.jar and fleetmap-spy, which starts lcm-spy with it.")

include(CPack)
