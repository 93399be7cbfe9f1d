#!/usr/bin/env bash
# Builds the package mrs_vpr_downstream in a new catkin workspace against mrs_vpr's devel space, as a
# user's package is built. Run by the downstream test.
#
# Usage: build_downstream.sh DEVEL_SETUP PACKAGE_DIR WORKSPACE    (WORKSPACE: an empty folder)
set -eo pipefail
devel_setup=${1:?usage: build_downstream.sh DEVEL_SETUP PACKAGE_DIR WORKSPACE}
package_dir=${2:?usage: build_downstream.sh DEVEL_SETUP PACKAGE_DIR WORKSPACE}
workspace=${3:?usage: build_downstream.sh DEVEL_SETUP PACKAGE_DIR WORKSPACE}

export PATH=/usr/bin:/bin:$PATH  # catkin's tools need Debian's python3.
# Started from `make run_tests`: the outer make's job server and flags are not this build's.
unset MAKEFLAGS MFLAGS MAKELEVEL
source "$devel_setup"

mkdir -p "$workspace/src"
cp -rL "$package_dir" "$workspace/src/"
cd "$workspace"
# One file to compile: well under a minute; a hung build fails instead of stalling the tests.
timeout 55 catkin_make -DCMAKE_BUILD_TYPE=Release -DCATKIN_ENABLE_TESTING=OFF
