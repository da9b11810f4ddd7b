#!/bin/sh
# A compiler/linker launcher that records each step's CPU time (user+sys, which hardly depends on
# how busy the machine is), wall time and peak memory, one line per step, to $BIMLOC_BUILD_TIME_LOG:
#   cmake -S . -B build-measure -DCMAKE_CXX_COMPILER_LAUNCHER=$PWD/scripts/build_time.sh \
#         -DCMAKE_CXX_LINKER_LAUNCHER=$PWD/scripts/build_time.sh
#   CCACHE_DISABLE=1 BIMLOC_BUILD_TIME_LOG=$PWD/build-measure/times.tsv cmake --build build-measure -j1
#   python3 scripts/build_time_report.py build-measure/times.tsv
# Columns: user_s sys_s wall_s maxrss_kb output (the argument after -o).
log=${BIMLOC_BUILD_TIME_LOG:-/dev/null}
out=?
prev=
for a in "$@"; do
  [ "$prev" = "-o" ] && out=$a
  prev=$a
done
exec /usr/bin/time -a -o "$log" -f "%U	%S	%e	%M	$PWD/$out" "$@"
