#!/bin/sh
# Install what zview needs to build and test, on Debian or Ubuntu.
# Run as root (or through sudo). Safe to run again.
set -e
# libassimp-dev is optional for the build (glTF, FBX, 3DS, ... through
# assimp; make ASSIMP=0 builds without it), not for the tests: make test
# fails on the checks a missing tool makes it skip (tests/skips.sh).
# tmux drives the viewer's end-to-end tests; python3 reads colours out of
# their screens (tests/e2e/looks.py), decodes PNG sizes and plays a slow
# terminal link (slowpty.py). libpng-dev and libjpeg-dev decode textures;
# zlib1g-dev reads gzip-compressed models (x.stl.gz).
# libseccomp-dev builds the filter of the loading sandbox (src/sandbox);
# strace shows its tests what a load opened and how its result came back.
# assimp-testmodels is Debian's corpus of assimp's test files
# (/usr/share/assimp/models): the up-axis tests read models from it, and
# the texture tests its textured models (tests/test_surface.c: glTF, GLB,
# data: URIs, COLLADA, OBJ).
# xvfb, xterm and imagemagick: a real terminal that draws sixel, looked
# at through a screenshot (tests/e2e/test_xterm.sh). kitty, with the
# software OpenGL it draws with under Xvfb (libgl1, libgl1-mesa-dri) and
# a monospace font: a real terminal that answers the kitty graphics
# query, and draws the viewer's pictures in its pixels (long_kitty.sh, make test-long).
# mlterm: a second real terminal that draws sixel (long_mlterm.sh, make test-long);
# screen: GNU screen, in which the viewer keeps cells and says why
# (long_mux.sh, make test-long, which also runs tmux inside xterm -ti vt340).
# admesh: the STL repair tool --repair is held against on broken parts
# (tests/e2e/test_repair_parts.sh, tools/repair-table.sh).
# lf and fzf: the file manager and the finder whose previews
# doc/previewers.md's recipes give (tests/e2e/test_previewers.sh).
# OpenCASCADE 7.6 (libocct-*-dev): STEP, IGES and BREP, optional for the
# build (the Makefile builds the shim libzview-occt.so when its headers
# are there; make OCCT=0 builds without), not for the tests: the data
# exchange readers (STEP, IGES, XCAF), the modelling algorithms (the
# mesher; the primitives tools/occtgen.cpp writes the test files with)
# and OCAF (the XCAF document the readers fill): tests/e2e/test_step.sh.
PKGS="build-essential pkg-config libncurses-dev libpng-dev libjpeg-dev zlib1g-dev libseccomp-dev libcriterion-dev tmux python3 strace libassimp-dev assimp-testmodels xvfb xterm imagemagick kitty libgl1 libgl1-mesa-dri fonts-dejavu-core admesh lf fzf libocct-data-exchange-dev libocct-modeling-algorithms-dev libocct-ocaf-dev mlterm screen"
SUDO=
[ "$(id -u)" -eq 0 ] || SUDO=sudo
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends $PKGS >/dev/null
echo "deps: installed $PKGS"
# make fuzz only: clang and its sanitizer + libFuzzer runtime (a package of
# its own on Debian 12); the build and tests above do not need them
FUZZ_PKGS="clang libclang-rt-dev"
if $SUDO apt-get install -y -qq --no-install-recommends $FUZZ_PKGS >/dev/null; then
    echo "deps: installed $FUZZ_PKGS"
else
    echo "deps: could not install $FUZZ_PKGS (needed by make fuzz only)"
fi
# The benchmarks only (no test needs them): f3d, which a STEP part's
# first picture (tools/bench-step.sh) and the dragon's -o
# (tools/bench-speed.sh; f3d runs under xvfb, installed above) are timed
# against; EGL's and OpenGL's headers, for tools/glref.c, the llvmpipe reference
# of make bench-speed (Mesa's llvmpipe is libgl1-mesa-dri, above)
BENCH_PKGS="f3d libegl-dev libgl1-mesa-dev"
if $SUDO apt-get install -y -qq --no-install-recommends $BENCH_PKGS >/dev/null; then
    echo "deps: installed $BENCH_PKGS"
else
    echo "deps: could not install $BENCH_PKGS (needed by make bench-step and make bench-speed only)"
fi
