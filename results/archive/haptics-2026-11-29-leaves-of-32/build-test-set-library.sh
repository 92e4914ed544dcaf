#!/bin/bash
# Builds ${LIB:-libab.a}: the collision sources of /work/main (at d6bebd7 for the stored runs),
# the avx512_on_avx2 test set replaced by a copy of 6a456f6's kernels: OLD=head-avx2-kernels-as-test-set
# (default) or head-avx512-kernels-as-test-set, compiled from old/, which holds those .cpp files
# and 6a456f6's kernel_lanes.inc, traversal.inc, kernel_set.inc and kernels.hpp
# (git show 6a456f6:collision/src/FILE > old/FILE).
set -e
M=/work/main; cd "$(dirname "$0")"; rm -rf obj; mkdir -p obj
F="-I$M/collision/include -I$M/collision/src -I$M/core/include -I$M/scene/include -O3 -DNDEBUG -ffp-contract=off -Wno-psabi -std=c++20"
for f in $M/collision/src/*.cpp; do b=$(basename $f .cpp); [ $b = kernels_avx512_on_avx2 ] && continue; g++ $F -c $f -o obj/$b.o & done
g++ $F -c old/${OLD:-head-avx2-kernels-as-test-set}.cpp -o obj/kernels_old.o
wait
rm -f ${LIB:-libab.a}; ar rcs ${LIB:-libab.a} obj/*.o
