# RockDEM's prerequisites, checked before anything else is configured.
#
# Each check looks for one thing the build, the tests or the main job need and, when it
# is missing, names the Debian 12 package that provides it. All checks run, then one
# error lists every missing package, so a new user sees
#
#   RockDEM: missing prerequisites (Debian 12 packages in brackets):
#     Qt5 OpenGL module (Qt5::OpenGL, linked by VTK::GUISupportQt)  [libqt5opengl5-dev]
#   Install them with: bash scripts/install-deps.sh
#
# instead of a generate-step error from deep inside ParaView's CMake config.
# scripts/install-deps.sh installs exactly the packages named here (a test,
# Build.PrerequisitesMatchInstallDeps, keeps the two lists in step).

set(_rockdem_missing)
set(ROCKDEM_PREREQUISITE_PACKAGES)

# _rockdem_need(<what> <debian package> <found?>)
macro(_rockdem_need what package found)
  list(APPEND ROCKDEM_PREREQUISITE_PACKAGES "${package}")
  if(NOT ${found})
    list(APPEND _rockdem_missing "  ${what}  [${package}]")
  endif()
endmacro()

# A package found by CMake's find_package (quietly, so that the summary speaks).
macro(_rockdem_need_package what package name)
  find_package(${name} QUIET ${ARGN})
  if(${name}_FOUND)
    set(_rockdem_found TRUE)
  else()
    set(_rockdem_found FALSE)
  endif()
  _rockdem_need("${what}" "${package}" _rockdem_found)
endmacro()

# A program on PATH.
macro(_rockdem_need_program what package var)
  find_program(${var} NAMES ${ARGN})
  if(${var})
    set(_rockdem_found TRUE)
  else()
    set(_rockdem_found FALSE)
  endif()
  _rockdem_need("${what}" "${package}" _rockdem_found)
endmacro()

# --- the engine --------------------------------------------------------------------
_rockdem_need_package("Eigen 3 (Eigen3Config.cmake)" libeigen3-dev Eigen3 NO_MODULE)
set(HDF5_PREFER_PARALLEL OFF)
_rockdem_need_package("HDF5 C library (serial)" libhdf5-dev HDF5 COMPONENTS C)
_rockdem_need_program("glslc (GLSL -> SPIR-V compiler)" glslc GLSLC_EXECUTABLE glslc)
_rockdem_need_package("Vulkan headers and loader" libvulkan-dev Vulkan)

# --- the plugin: ParaView and what its CMake config needs ----------------------------
if(ROCKDEM_BUILD_PLUGIN)
  _rockdem_need_package("MPI C library (ParaView's config asks for it)" libopenmpi-dev MPI COMPONENTS C)
  set(_pv_candidates)
  foreach(_prefix IN LISTS CMAKE_PREFIX_PATH CMAKE_SYSTEM_PREFIX_PATH)
    list(APPEND _pv_candidates "${_prefix}/lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/paraview-5.11"
                               "${_prefix}/lib/cmake/paraview-5.11")
  endforeach()
  find_file(ROCKDEM_PARAVIEW_CONFIG NAMES ParaViewConfig.cmake paraview-config.cmake PATHS ${_pv_candidates} NO_DEFAULT_PATH)
  if(ParaView_DIR AND EXISTS "${ParaView_DIR}/paraview-config.cmake")
    set(ROCKDEM_PARAVIEW_CONFIG "${ParaView_DIR}/paraview-config.cmake")
  endif()
  _rockdem_need("ParaView 5.11 development files (paraview-config.cmake)" paraview-dev ROCKDEM_PARAVIEW_CONFIG)
  # The Qt modules that ParaView's and VTK's exported targets link (pqCore,
  # VTK::GUISupportQt): a missing one passes configure and fails at generate.
  foreach(_qt IN ITEMS Core:qtbase5-dev Gui:qtbase5-dev Widgets:qtbase5-dev Network:qtbase5-dev
                       OpenGL:libqt5opengl5-dev Svg:libqt5svg5-dev Help:qttools5-dev)
    string(REPLACE ":" ";" _qt "${_qt}")
    list(GET _qt 0 _qt_module)
    list(GET _qt 1 _qt_package)
    find_package(Qt5${_qt_module} QUIET)
    if(Qt5${_qt_module}_FOUND)
      set(_rockdem_found TRUE)
    else()
      set(_rockdem_found FALSE)
    endif()
    _rockdem_need("Qt5 ${_qt_module} module (Qt5::${_qt_module}, linked by ParaView/VTK targets)"
      "${_qt_package}" _rockdem_found)
  endforeach()
  # /usr/bin/xmlpatterns is qtchooser's wrapper, present without the tool itself.
  _rockdem_need_program("xmlpatterns (ParaView's plugin documentation step)" qtxmlpatterns5-dev-tools
    ROCKDEM_XMLPATTERNS xmlpatterns PATHS /usr/lib/qt5/bin "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/qt5/bin" NO_DEFAULT_PATH)
  # Third-party libraries whose CMake find modules ParaView's config runs (VTK's modules,
  # shipped beside ParaView's config).
  if(ROCKDEM_PARAVIEW_CONFIG)
    get_filename_component(_pv_dir "${ROCKDEM_PARAVIEW_CONFIG}" DIRECTORY)
    set(_rockdem_saved_module_path "${CMAKE_MODULE_PATH}")
    list(APPEND CMAKE_MODULE_PATH "${_pv_dir}/vtk")
    _rockdem_need_package("double-conversion" libdouble-conversion-dev double-conversion)
    _rockdem_need_package("LZ4" liblz4-dev LZ4)
    _rockdem_need_package("LZMA" liblzma-dev LZMA)
    _rockdem_need_package("zlib" zlib1g-dev ZLIB)
    _rockdem_need_package("Expat" libexpat1-dev EXPAT)
    _rockdem_need_package("utf8cpp" libutfcpp-dev utf8cpp)
    _rockdem_need_package("FreeType" libfreetype-dev Freetype)
    _rockdem_need_package("GLEW" libglew-dev GLEW)
    _rockdem_need_package("gl2ps" libgl2ps-dev GL2PS)
    _rockdem_need_package("JPEG" libjpeg-dev JPEG)
    _rockdem_need_package("PNG" libpng-dev PNG)
    _rockdem_need_package("TIFF" libtiff-dev TIFF)
    _rockdem_need_package("LibXml2" libxml2-dev LibXml2)
    _rockdem_need_package("X11" libx11-dev X11)
    _rockdem_need_package("OpenGL" libgl-dev OpenGL)
    _rockdem_need_package("Theora" libtheora-dev THEORA)
    _rockdem_need_package("NetCDF" libnetcdf-dev NetCDF)
    _rockdem_need_package("JsonCpp" libjsoncpp-dev JsonCpp)
    _rockdem_need_package("pugixml" libpugixml-dev pugixml)
    _rockdem_need_package("Protobuf" libprotobuf-dev Protobuf)
    set(CMAKE_MODULE_PATH "${_rockdem_saved_module_path}")
  endif()
endif()

# --- tests and the main job ------------------------------------------------------------
if(ROCKDEM_BUILD_TESTING)
  _rockdem_need_package("GoogleTest" libgtest-dev GTest)
  if(ROCKDEM_BUILD_PLUGIN)
    _rockdem_need_program("pvbatch" paraview PVBATCH_EXECUTABLE pvbatch)
    _rockdem_need_program("pvpython and ParaView's Python modules" python3-paraview PVPYTHON_EXECUTABLE pvpython)
    _rockdem_need_program("Xvfb (rendering without a display; scripts/run_with_xvfb.sh)" xvfb XVFB_EXECUTABLE Xvfb)
  endif()
endif()

if(_rockdem_missing)
  list(REMOVE_DUPLICATES _rockdem_missing)
  string(REPLACE ";" "\n" _rockdem_missing_text "${_rockdem_missing}")
  message(FATAL_ERROR
    "RockDEM: missing prerequisites (Debian 12 packages in brackets):\n"
    "${_rockdem_missing_text}\n"
    "Install them with: bash scripts/install-deps.sh")
endif()
list(REMOVE_DUPLICATES ROCKDEM_PREREQUISITE_PACKAGES)
message(STATUS "RockDEM: all prerequisites found")
# For the test that install-deps.sh installs every package named here.
string(REPLACE ";" "\n" _rockdem_packages_text "${ROCKDEM_PREREQUISITE_PACKAGES}")
file(WRITE "${CMAKE_BINARY_DIR}/prerequisite_packages.txt" "${_rockdem_packages_text}\n")
