include(${CMAKE_CURRENT_LIST_DIR}/run_checked.cmake)

file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
run_checked(COMMAND ${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f include/macrocon/macrocon.h include/macrocon/macrocon.hpp lib/pkgconfig/macrocon.pc
          lib/cmake/macrocon/macrocon-config.cmake lib/cmake/macrocon/macrocon-config-version.cmake
          share/doc/macrocon/LICENSE share/doc/macrocon/THIRD_PARTY_NOTICES share/macrocon/starter.mclb)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "missing after install: ${f}")
  endif()
endforeach()
# The installed licence is the repository's (Apache-2.0), the notices name every linked library.
file(SHA256 ${prefix}/share/doc/macrocon/LICENSE installed_licence)
file(SHA256 ${SRC}/LICENSE source_licence)
file(READ ${prefix}/share/doc/macrocon/LICENSE licence_text LIMIT 200)
if(NOT installed_licence STREQUAL source_licence OR NOT licence_text MATCHES "Apache License[ \n]+Version 2.0")
  message(FATAL_ERROR "share/doc/macrocon/LICENSE is not the repository's Apache-2.0 LICENSE")
endif()
file(READ ${prefix}/share/doc/macrocon/THIRD_PARTY_NOTICES notices)
foreach(name Eigen Spectra FlatBuffers oneTBB zlib MakeHuman "Mozilla Public License")
  string(FIND "${notices}" "${name}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "share/doc/macrocon/THIRD_PARTY_NOTICES does not mention ${name}")
  endif()
endforeach()
file(GLOB sonames ${prefix}/lib/libmacrocon.so.*)
if(NOT sonames)
  message(FATAL_ERROR "no versioned libmacrocon.so.* installed")
endif()

# 1. CMake package.
run_checked(COMMAND ${CMAKE_COMMAND} -S ${SRC}/packaging/consumer -B ${WORK}/cmake-build -G ${GENERATOR}
            -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
run_checked(COMMAND ${CMAKE_COMMAND} --build ${WORK}/cmake-build)
foreach(exe consumer_c consumer_cpp)
  run_checked(OUTPUT_VARIABLE out COMMAND ${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${prefix}/lib ${WORK}/cmake-build/${exe})
  message(STATUS "${exe} (CMake): ${out}")
endforeach()

# 2. pkg-config.
file(MAKE_DIRECTORY ${WORK}/pc-build)
run_checked(WHAT "pkg-config cannot find macrocon" OUTPUT_VARIABLE flags
  COMMAND ${CMAKE_COMMAND} -E env PKG_CONFIG_PATH=${prefix}/lib/pkgconfig pkg-config --cflags --libs macrocon)
string(STRIP "${flags}" flags)
separate_arguments(flags UNIX_COMMAND "${flags}")
run_checked(COMMAND cc -std=c99 -Wall -Wextra -Werror -pedantic ${SRC}/packaging/consumer/consumer.c ${flags} -o ${WORK}/pc-build/consumer_c)
run_checked(COMMAND c++ -std=c++17 -Wall -Wextra -Werror ${SRC}/packaging/consumer/consumer.cpp ${flags} -o ${WORK}/pc-build/consumer_cpp)
foreach(exe consumer_c consumer_cpp)
  run_checked(OUTPUT_VARIABLE out COMMAND ${CMAKE_COMMAND} -E env LD_LIBRARY_PATH=${prefix}/lib ${WORK}/pc-build/${exe})
  message(STATUS "${exe} (pkg-config): ${out}")
endforeach()
