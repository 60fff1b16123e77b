# FindZoltan: locate the Zoltan partitioning library (Debian: libtrilinos-zoltan-dev,
# which installs zoltan.h under /usr/include/trilinos and libtrilinos_zoltan.so).
# Defines Zoltan_FOUND, Zoltan_INCLUDE_DIRS, Zoltan_LIBRARIES and the imported
# target Zoltan::Zoltan. Zoltan needs MPI, so callers find MPI first.
find_path(Zoltan_INCLUDE_DIR zoltan.h PATH_SUFFIXES trilinos)
find_library(Zoltan_LIBRARY NAMES trilinos_zoltan zoltan)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(Zoltan REQUIRED_VARS Zoltan_LIBRARY Zoltan_INCLUDE_DIR)

if(Zoltan_FOUND)
  set(Zoltan_INCLUDE_DIRS ${Zoltan_INCLUDE_DIR})
  set(Zoltan_LIBRARIES ${Zoltan_LIBRARY})
  if(NOT TARGET Zoltan::Zoltan)
    add_library(Zoltan::Zoltan UNKNOWN IMPORTED)
    set_target_properties(Zoltan::Zoltan PROPERTIES IMPORTED_LOCATION "${Zoltan_LIBRARY}"
                          INTERFACE_INCLUDE_DIRECTORIES "${Zoltan_INCLUDE_DIR}")
  endif()
endif()
mark_as_advanced(Zoltan_INCLUDE_DIR Zoltan_LIBRARY)
