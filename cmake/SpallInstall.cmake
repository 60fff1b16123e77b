# Installable libspall (issue 23 item 3): `cmake --install BUILD --prefix P`
# (or `make install PREFIX=P`) puts into P
#   bin/spall                                 the command-line program
#   lib/libspall.so.VERSION (+ .so.0, .so)    shared library, public symbols only
#   lib/libspall.a                            static library (PIC objects)
#   include/spall/*.h                         the public headers
#   lib/pkgconfig/spall.pc                    pkg-config (--static for the archive)
#   lib/cmake/spall/spallConfig.cmake         find_package(spall): spall::spall
#                                             (shared), spall::spall_static
# Validation cases and benchmarks (libspall_validation, libspall_bench) are
# not part of the installed library: the CLI links them statically.
#
# Included last from CMakeLists.txt, so that the link lines of spall_lib are
# final here (whatever other modules added: MPI, parallel HDF5, Zoltan ...):
# the installed static library's dependencies are read from spall_lib.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The public C API (include/spall/sim.h) is part of libspall.
file(GLOB SPALL_API_SOURCES CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/api/*.c)
target_sources(spall_lib PRIVATE ${SPALL_API_SOURCES})

# One compilation serves the build tree's static spall_lib and both installed
# libraries, so every object is position independent (cheap on x86-64).
set_target_properties(spall_lib PROPERTIES POSITION_INDEPENDENT_CODE ON)

# Flatten the link dependencies of spall_lib into plain items (full paths,
# -l / -Wl flags) that a consumer outside this build can use: imported
# targets (PkgConfig::*, OpenMP::OpenMP_C, MPI::MPI_C ...) do not exist
# there.  Recurses through INTERFACE_LINK_LIBRARIES; LINK_ONLY wrappers are
# unwrapped, other generator expressions are refused loudly.
function(spall_flatten_link_items out)
  set(items "")
  foreach(item IN LISTS ARGN)
    if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
      set(item "${CMAKE_MATCH_1}")
    endif()
    if(item MATCHES "^\\$<")
      message(FATAL_ERROR "SpallInstall: cannot flatten link item '${item}' of spall_lib")
    endif()
    if(TARGET ${item})
      get_target_property(type ${item} TYPE)
      get_target_property(imported ${item} IMPORTED)
      if(imported AND NOT type STREQUAL "INTERFACE_LIBRARY")
        get_target_property(loc ${item} IMPORTED_LOCATION)
        if(NOT loc)
          get_target_property(loc ${item} IMPORTED_LOCATION_RELEASE)
        endif()
        if(loc)
          list(APPEND items "${loc}")
        endif()
      elseif(NOT imported)
        message(FATAL_ERROR "SpallInstall: spall_lib links the build target '${item}', "
                            "which the installed library does not carry")
      endif()
      get_target_property(sub ${item} INTERFACE_LINK_LIBRARIES)
      if(sub)
        spall_flatten_link_items(sub_items ${sub})
        list(APPEND items ${sub_items})
      endif()
      get_target_property(opts ${item} INTERFACE_LINK_OPTIONS)
      if(opts)
        list(APPEND items ${opts})
      endif()
    elseif(item MATCHES "^(/|-)")
      list(APPEND items "${item}")
    elseif(NOT item STREQUAL "")
      list(APPEND items "-l${item}")
    endif()
  endforeach()
  list(REMOVE_DUPLICATES items)
  set(${out} "${items}" PARENT_SCOPE)
endfunction()

get_target_property(SPALL_LIB_LINKS spall_lib LINK_LIBRARIES)
spall_flatten_link_items(SPALL_DEP_ITEMS ${SPALL_LIB_LINKS})

# The installed libraries: the objects of spall_lib, linked once more.  They
# live in their own folder so that the build tree's libspall.a (spall_lib,
# used by the CLI and the tests) keeps its name.
set(SPALL_INSTALL_LIB_DIR ${CMAKE_BINARY_DIR}/installed-lib)
add_library(spall_shared SHARED $<TARGET_OBJECTS:spall_lib>)
add_library(spall_static STATIC $<TARGET_OBJECTS:spall_lib>)
set_target_properties(spall_shared PROPERTIES
  OUTPUT_NAME spall VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}
  LIBRARY_OUTPUT_DIRECTORY ${SPALL_INSTALL_LIB_DIR}
  EXPORT_NAME spall
  # Only the public API (spall_*, pen_*) is exported: the internals stay
  # free to change without breaking the shared library's users.
  LINK_DEPENDS ${CMAKE_SOURCE_DIR}/cmake/libspall.map)
target_link_options(spall_shared PRIVATE -Wl,--version-script=${CMAKE_SOURCE_DIR}/cmake/libspall.map
                    -Wl,--no-undefined)
target_link_libraries(spall_shared PRIVATE ${SPALL_DEP_ITEMS})
set_target_properties(spall_static PROPERTIES
  OUTPUT_NAME spall ARCHIVE_OUTPUT_DIRECTORY ${SPALL_INSTALL_LIB_DIR} EXPORT_NAME spall_static)
target_link_libraries(spall_static INTERFACE ${SPALL_DEP_ITEMS})
foreach(t spall_shared spall_static)
  target_include_directories(${t} INTERFACE $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
endforeach()

install(TARGETS spall RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS spall_shared spall_static EXPORT spallTargets
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(DIRECTORY ${CMAKE_SOURCE_DIR}/include/spall DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
# the example program of docs/api.md, to be copied and built by a user
install(FILES ${CMAKE_SOURCE_DIR}/examples/api/plate.c ${CMAKE_SOURCE_DIR}/examples/api/plate.yaml
              ${CMAKE_SOURCE_DIR}/examples/api/Makefile ${CMAKE_SOURCE_DIR}/examples/api/CMakeLists.txt
        DESTINATION ${CMAKE_INSTALL_DATADIR}/spall/examples/api)

set(SPALL_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/spall)
install(EXPORT spallTargets NAMESPACE spall:: DESTINATION ${SPALL_CMAKE_DIR})
configure_package_config_file(${CMAKE_SOURCE_DIR}/cmake/spallConfig.cmake.in
                              ${CMAKE_BINARY_DIR}/spallConfig.cmake
                              INSTALL_DESTINATION ${SPALL_CMAKE_DIR})
write_basic_package_version_file(${CMAKE_BINARY_DIR}/spallConfigVersion.cmake
                                 VERSION ${PROJECT_VERSION} COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/spallConfig.cmake ${CMAKE_BINARY_DIR}/spallConfigVersion.cmake
        DESTINATION ${SPALL_CMAKE_DIR})

# pkg-config: relocatable (prefix from the .pc file's own place), the static
# dependencies in Libs.private for `pkg-config --static --libs spall`.
string(REPLACE ";" " " SPALL_PC_LIBS_PRIVATE "${SPALL_DEP_ITEMS}")
file(RELATIVE_PATH SPALL_PC_TO_PREFIX /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)
string(REGEX REPLACE "/$" "" SPALL_PC_TO_PREFIX "${SPALL_PC_TO_PREFIX}")
configure_file(${CMAKE_SOURCE_DIR}/cmake/spall.pc.in ${CMAKE_BINARY_DIR}/spall.pc @ONLY)
install(FILES ${CMAKE_BINARY_DIR}/spall.pc DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

# ctest api_install: install into a scratch prefix, build examples/api
# against it with find_package(spall) and with pkg-config, run both.
# Not under ASan: the installed libraries would need the sanitizer runtime
# in every consumer's link line.
if(SPALL_TESTS)
  add_test(NAME api_install
           COMMAND bash ${CMAKE_SOURCE_DIR}/tests/api_install.sh ${CMAKE_BINARY_DIR}
                   ${CMAKE_SOURCE_DIR} ${CMAKE_COMMAND})
  set_tests_properties(api_install PROPERTIES LABELS no_asan TIMEOUT 600
                       ENVIRONMENT "OMP_NUM_THREADS=2;OMP_WAIT_POLICY=passive")
endif()
