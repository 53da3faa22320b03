#!/usr/bin/env bash
# Installs every Debian 12 package ALOHA needs. Idempotent: does nothing (and touches no network)
# when all packages are already installed. Run as root (or with sudo available).
set -euo pipefail

PACKAGES=(
  cmake ninja-build g++ pkg-config git         # toolchain
  libvulkan-dev mesa-vulkan-drivers             # Vulkan headers + loader, lavapipe (software GPU)
  vulkan-validationlayers vulkan-tools          # validation layers (tests fail on any message)
  glslang-dev glslang-tools spirv-tools         # GLSL -> SPIR-V at build time and in-process
  libglm-dev                                    # vector / matrix / quaternion maths
  libglfw3-dev                                  # the viewer window
  libtinygltf-dev                               # glTF characters
  libosd-dev                                    # OpenSubdiv Catmull-Clark refinement
  libmeshoptimizer-dev                          # vertex-cache order of the generated body skin; EXT_meshopt_compression glTF
  gltfpack                                      # tests: writes the quantised and compressed glTF files the loader reads
  libdraco-dev                                  # Draco-compressed glTF meshes (KHR_draco_mesh_compression)
  libeigen3-dev                                 # linear algebra of the IK and dynamics solvers
  libcli11-dev                                  # the aloha tool's command line (subcommands, checks, help)
  nlohmann-json3-dev                            # scene and rule files
  libtbb-dev                                    # scheduler thread pool / parallel loops
  libimgui-dev                                  # viewer overlay
  libpng-dev                                    # PNG output
  libstb-dev                                    # stb_image: glTF base colour textures
  libwebp-dev                                   # WebP glTF textures (EXT_texture_webp)
  libgtest-dev libgmock-dev libbenchmark-dev    # tests and benchmarks
  xvfb xauth                                    # viewer tests under a virtual X server
  clang libclang-rt-14-dev                      # libFuzzer targets
)

missing=()
for p in "${PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages present"
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
