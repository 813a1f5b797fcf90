#!/bin/bash
# Packs a Release build of gbufferlab and the shared libraries it needs beyond the C/C++ runtime
# into .carry/ (bin/, lib/), for a machine that has none of the build's packages: a lent GPU
# machine (Ubuntu, no package registry) running `bench/run.sh gpu4k` or a test on its GPU. The
# working tree travels with the shaders and layouts, so only binaries and libraries are packed.
#
# usage: bench/carry.sh [EXTRA_BINARY...]   e.g. bench/carry.sh gpu_evaluator_test gpu_cpu_bits_test
# environment: GBL_BENCH_BUILD_DIR (default build-bench; built here, Release, unless
#   GBL_BENCH_NO_BUILD=1)
#
# Then, on the lent machine (the Vulkan loader from Debian's packages in .gl/, as the device
# tool's README says), with .carry and .gl named in the run's carry list:
#   for f in .gl/*.deb; do dpkg -x $f /; done; ldconfig; . .carry/env.sh
#   GBL_BENCH_NO_BUILD=1 GBL_BENCH_BUILD_DIR=.carry/bin bench/run.sh gpu4k
# .carry/env.sh points LD_LIBRARY_PATH at .carry/lib, and GBL_SHADER_DIR and GBL_LAYOUT_DIR at the
# working tree beside it: the binaries' built-in paths are this checkout's, which the lent machine
# does not have.
# Left out: the C and C++ runtime (glibc, libstdc++, libgcc_s: a newer system's serve a binary
# built against older ones) and the Vulkan loader (the machine's, or .gl's, finds its driver).
set -euo pipefail
cd "$(dirname "$0")/.."

build=${GBL_BENCH_BUILD_DIR:-build-bench}
binaries=(gbufferlab "$@")
if [ -z "${GBL_BENCH_NO_BUILD:-}" ]; then
    cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DGBL_BUILD_BENCH=ON >/dev/null
    cmake --build "$build" --target "${binaries[@]}" -j2
fi
for b in "${binaries[@]}"; do
    [ -x "$build/$b" ] || { echo "carry: $build/$b is not built; build it or name another binary" >&2; exit 2; }
done

# .carry must be ignored by git for the device tool to take it as a carried path.
grep -qx '/.carry/' .git/info/exclude 2>/dev/null || echo '/.carry/' >>.git/info/exclude
rm -rf .carry
mkdir -p .carry/bin .carry/lib
for b in "${binaries[@]}"; do cp "$build/$b" .carry/bin/; done
# Every library the binaries load, but the runtime's and the loader's.
ldd .carry/bin/* | awk '$2 == "=>" && $3 ~ /^\// { print $3 }' | sort -u | while read -r lib; do
    case "$(basename "$lib")" in
        libc.so.* | libm.so.* | libpthread.so.* | libdl.so.* | librt.so.* | ld-linux*.so.* | libstdc++.so.* | \
            libgcc_s.so.* | libvulkan.so.*) ;;
        *) cp -L "$lib" .carry/lib/ ;;
    esac
done
cat >.carry/env.sh <<'ENV'
# Sourced on the lent machine from the working tree's root (bench/carry.sh).
carry_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
export LD_LIBRARY_PATH="$carry_root/.carry/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
export GBL_SHADER_DIR="$carry_root/shaders" GBL_LAYOUT_DIR="$carry_root/layouts"
ENV
# The bundle must resolve everything it packed from .carry/lib (a library missing here would
# only show on the lent machine, after its minutes started).
missing=$(LD_LIBRARY_PATH=$PWD/.carry/lib ldd .carry/bin/* | awk '$2 == "=>" && $3 == "not" { print $1 }' | sort -u)
[ -z "$missing" ] || { echo "carry: not found: $missing" >&2; exit 1; }
echo "carry: $(ls .carry/bin | wc -l) binaries, $(ls .carry/lib | wc -l) libraries, $(du -sh .carry | cut -f1) in .carry/"
ls .carry/lib
