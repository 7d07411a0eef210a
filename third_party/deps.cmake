# Turns Debian 12 system packages into CMake targets. Nothing here is vendored or downloaded:
# scripts/setup.sh installs the packages, this file only finds them.
find_package(Eigen3 3.4 REQUIRED NO_MODULE)
find_package(OpenMP REQUIRED)
find_package(nlohmann_json 3.10 REQUIRED)
find_package(CLI11 2.1 REQUIRED)
find_package(PNG REQUIRED)
# Float EXR heightmaps and maps (Debian libopenexr-dev).
find_package(OpenEXR 3.1 REQUIRED CONFIG)
# Elevation data (GeoTIFF, SRTM .hgt, ASCII grid) in and GeoTIFF out (Debian libgdal-dev).
find_package(GDAL 3.6 REQUIRED CONFIG)
# The terrain as a glTF mesh (Debian libtinygltf-dev, a shared library there).
find_package(TinyGLTF 2.7 REQUIRED CONFIG)
# nanoflann (libnanoflann-dev, header-only): the kd-tree neighbor search, engine.neighbor_search.
find_package(nanoflann 1.4 REQUIRED)

# Catch2 2.x ships a single header (catch2/catch.hpp) and a CMake config.
find_package(Catch2 2.13 REQUIRED)

# stb (libstb-dev): headers under /usr/include/stb, implementation in libstb.
find_path(STB_INCLUDE_DIR stb_image.h PATH_SUFFIXES stb REQUIRED)
find_library(STB_LIBRARY stb REQUIRED)
add_library(scour_stb INTERFACE)
target_include_directories(scour_stb SYSTEM INTERFACE ${STB_INCLUDE_DIR})
target_link_libraries(scour_stb INTERFACE ${STB_LIBRARY})

# Rendering: GLEW, GLFW, EGL and OSMesa (Mesa). OSMesa is linked before libGL: its exported gl*
# entry points go through Mesa's shared glapi dispatch, which serves EGL and GLX contexts of Mesa
# as well, so the same binary renders through all three (src/render/context.cpp explains).
find_package(OpenGL REQUIRED COMPONENTS OpenGL EGL)
find_package(GLEW 2.1 REQUIRED)
find_package(glfw3 3.3 REQUIRED)
find_package(PkgConfig REQUIRED)
pkg_check_modules(OSMESA REQUIRED IMPORTED_TARGET osmesa)
