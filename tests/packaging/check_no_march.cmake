# The package exports no target-CPU flags: a user's binary must not be built for the CPU of the
# machine that built or installed sphbasis (the project's own binaries use -march=native or
# SPHBASIS_MARCH through a private target). Fails if an installed CMake or pkg-config file names
# -march, -mtune, -mavx*, -mfma or -msse*.
# Usage: cmake -DPREFIX=<install prefix> -P check_no_march.cmake
file(GLOB_RECURSE files ${PREFIX}/*.cmake ${PREFIX}/*.pc)
list(LENGTH files n)
if(n EQUAL 0)
  message(FATAL_ERROR "check_no_march: no CMake or pkg-config files under ${PREFIX}")
endif()
foreach(f ${files})
  file(READ ${f} text)
  if(text MATCHES "-m(arch|tune|avx|fma|sse)[-=0-9a-z]*")
    message(FATAL_ERROR "check_no_march: ${f} exports '${CMAKE_MATCH_0}'")
  endif()
endforeach()
message(STATUS "check_no_march: ${n} files, no target-CPU flag")
