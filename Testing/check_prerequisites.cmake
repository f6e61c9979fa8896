# Build.Prerequisites: the configure-time checks of cmake/RockDEMPrerequisites.cmake.
#  1. Every Debian package those checks name is installed by scripts/install-deps.sh.
#  2. A configure with a prerequisite hidden (CMAKE_DISABLE_FIND_PACKAGE_<name>) stops at
#     once with an error that names the missing Debian package, instead of failing later.
# cmake -DSOURCE_DIR=... -DBINARY_DIR=... -DSCRATCH_DIR=... -P check_prerequisites.cmake
file(READ "${SOURCE_DIR}/scripts/install-deps.sh" _deps)
file(STRINGS "${BINARY_DIR}/prerequisite_packages.txt" _packages)
set(_failures 0)
foreach(_p IN LISTS _packages)
  if(_p AND NOT _deps MATCHES "[ \n]${_p}[ \n]")
    message(SEND_ERROR "scripts/install-deps.sh does not install ${_p}, which configuring needs")
    math(EXPR _failures "${_failures} + 1")
  endif()
endforeach()
list(LENGTH _packages _n)
message(STATUS "install-deps.sh installs all ${_n} packages the configure checks name")

foreach(_case IN ITEMS "Qt5OpenGL:libqt5opengl5-dev" "HDF5:libhdf5-dev" "Eigen3:libeigen3-dev"
                       "GTest:libgtest-dev" "MPI:libopenmpi-dev" "LZ4:liblz4-dev")
  string(REPLACE ":" ";" _case "${_case}")
  list(GET _case 0 _name)
  list(GET _case 1 _package)
  set(_dir "${SCRATCH_DIR}/${_name}")
  file(REMOVE_RECURSE "${_dir}")
  execute_process(
    COMMAND "${CMAKE_COMMAND}" -S "${SOURCE_DIR}" -B "${_dir}" -G Ninja
            "-DCMAKE_DISABLE_FIND_PACKAGE_${_name}=ON"
    RESULT_VARIABLE _rc OUTPUT_VARIABLE _out ERROR_VARIABLE _err)
  file(REMOVE_RECURSE "${_dir}")
  if(_rc EQUAL 0)
    message(SEND_ERROR "configure with ${_name} hidden succeeded")
    math(EXPR _failures "${_failures} + 1")
  elseif(NOT _err MATCHES "missing prerequisites" OR NOT _err MATCHES "\\[${_package}\\]")
    message(SEND_ERROR "configure with ${_name} hidden did not name ${_package}:\n${_err}")
    math(EXPR _failures "${_failures} + 1")
  else()
    message(STATUS "${_name} hidden: configure stops and names ${_package}")
  endif()
endforeach()
if(_failures GREATER 0)
  message(FATAL_ERROR "${_failures} prerequisite check(s) failed")
endif()
