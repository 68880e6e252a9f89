#!/usr/bin/env bash
# Installs what igi-cluster needs from Debian 12 packages. Idempotent: does
# nothing (and needs no network) when every package is already present.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  ccache                               # compiles shared by every build folder and clone (CMakeLists.txt)
  libembree-dev libtbb-dev
  libopenimageio-dev openimageio-tools
  libglfw3-dev libgl-dev libglm-dev libimgui-dev   # libimgui-dev: the window's panels (its GLFW and OpenGL 2 backends are in libimgui.a)
  libzmq3-dev cppzmq-dev
  libxxhash-dev                        # XXH3 content hashes (scenes, VPL sets)
  libzstd-dev liblz4-dev               # tile pixels compressed on the wire (--pixel-codec zstd, lz4)
  libavcodec-dev libavutil-dev libswscale-dev   # igi-view's moving frames as H.264 (libx264 comes with libavcodec)
  libtinygltf-dev nlohmann-json3-dev libstb-dev
  libtinyobjloader-dev                 # OBJ scenes (common/scene/obj_loader.cpp: the header alone)
  libcli11-dev                         # command-line options of every program
  libgtest-dev
  xvfb xauth libgl1-mesa-dri
  fonts-dejavu-core                    # the window panel's text at the sizes a small window needs
  xdotool                              # the window test that drags the mouse as a user does
  python3-venv
  clang-14 libclang-rt-14-dev
  openssh-client openssh-server        # scripts/launch-ssh.sh, and its test's own sshd on loopback
  slurm-wlm munge                      # scripts/launch-srun.sh, and its test's single-node Slurm
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
