# Finds the Debian packages ALOHA builds on. Included by the build and by alohaConfig.cmake.
include(CMakeFindDependencyMacro)
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json 3 CONFIG REQUIRED)
find_package(TBB CONFIG REQUIRED)
find_package(TinyGLTF CONFIG REQUIRED)
find_package(Vulkan REQUIRED)
find_package(Threads REQUIRED)
find_package(PNG REQUIRED)
find_package(meshoptimizer CONFIG REQUIRED)  # skin vertex-cache order (libmeshoptimizer-dev)
find_package(draco CONFIG REQUIRED)          # KHR_draco_mesh_compression glTF meshes (libdraco-dev; linked as draco::draco_static)
find_package(Eigen3 3.3 CONFIG REQUIRED)       # IK and dynamics linear algebra (libeigen3-dev)
find_package(PkgConfig REQUIRED)
pkg_check_modules(ALOHA_WEBP REQUIRED IMPORTED_TARGET GLOBAL libwebp)  # EXT_texture_webp glTF textures (libwebp-dev)
find_package(glfw3 3.3 CONFIG QUIET)  # only the viewer's window library (aloha::gpu_window) needs it

# OpenSubdiv 3.5 on Debian: its CMake config names a static libosdCPU.a the package lacks,
# so wrap the shared library in a target of our own.
if(NOT TARGET aloha_opensubdiv)
  find_library(ALOHA_OSD_CPU_LIBRARY osdCPU REQUIRED)
  find_path(ALOHA_OSD_INCLUDE_DIR opensubdiv/far/topologyRefiner.h REQUIRED)
  add_library(aloha_opensubdiv SHARED IMPORTED GLOBAL)
  set_target_properties(aloha_opensubdiv PROPERTIES
    IMPORTED_LOCATION ${ALOHA_OSD_CPU_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${ALOHA_OSD_INCLUDE_DIR})
endif()

# stb_image (Debian libstb-dev) decodes glTF base colour textures (PNG, JPEG).
if(NOT TARGET aloha_stb)
  find_library(ALOHA_STB_LIBRARY stb REQUIRED)
  find_path(ALOHA_STB_INCLUDE_DIR stb_image.h PATH_SUFFIXES stb REQUIRED)
  add_library(aloha_stb SHARED IMPORTED GLOBAL)
  set_target_properties(aloha_stb PROPERTIES
    IMPORTED_LOCATION ${ALOHA_STB_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${ALOHA_STB_INCLUDE_DIR})
endif()
