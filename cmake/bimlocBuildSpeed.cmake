# A fresh build in half the time (issue 30): unity batches and precompiled headers for our targets.
#
# Where the time went (scripts/build_time.sh, CPU seconds per translation unit): every unit parsed
# and instantiated the same standard library, Eigen, nlohmann json and gtest headers again, and
# wrote full debug information for all of it. A unity batch parses them once per batch; the
# precompiled header once per target.
#
#   -DBIMLOC_UNITY_BUILD=OFF   one object per source file again (e.g. to find a missing #include)
#   -DBIMLOC_PCH=OFF           no precompiled headers
option(BIMLOC_UNITY_BUILD "Compile each target's sources in unity batches" ON)
option(BIMLOC_PCH "Precompile the heavy third-party headers of each target" ON)

# The standard headers most of our sources include.
set(BIMLOC_PCH_STD <algorithm> <array> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <functional>
    <limits> <map> <memory> <optional> <set> <sstream> <stdexcept> <string> <utility> <vector>)

# bimloc_speed_up(TARGET [BATCH N] [PCH header...])
# Unity batches of N sources (in the order the target lists them, so a batch mostly holds one
# folder's sources, which include the same headers), and the headers given precompiled. Two
# sources of one batch share their anonymous namespaces: a helper defined in both is a
# "redefinition" error. Rename one (the name then says what it is for), or give the source
# SKIP_UNITY_BUILD_INCLUSION where its target is defined. Without BATCH: no unity batches.
function(bimloc_speed_up target)
  cmake_parse_arguments(ARG "" "BATCH" "PCH" ${ARGN})
  if(BIMLOC_UNITY_BUILD AND ARG_BATCH)
    set_target_properties(${target} PROPERTIES UNITY_BUILD ON UNITY_BUILD_BATCH_SIZE ${ARG_BATCH})
  endif()
  if(BIMLOC_PCH AND ARG_PCH)
    target_precompile_headers(${target} PRIVATE ${ARG_PCH})
    # ccache leaves a unit that uses a precompiled header uncached ("could not use precompiled
    # header") unless told that the header's macros and __TIME__ may be trusted.
    if(CMAKE_CXX_COMPILER_LAUNCHER MATCHES "ccache")
      set_property(TARGET ${target} PROPERTY CXX_COMPILER_LAUNCHER ${CMAKE_COMMAND} -E env
        CCACHE_SLOPPINESS=pch_defines,time_macros ${CMAKE_CXX_COMPILER_LAUNCHER})
    endif()
  endif()
endfunction()
