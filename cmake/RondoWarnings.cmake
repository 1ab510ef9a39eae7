# Compiler flags shared by every rondo target: warnings, optional -Werror and sanitizers.
add_library(rondo_build_flags INTERFACE)
target_compile_options(rondo_build_flags INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wsign-conversion -Wnon-virtual-dtor
  -Wold-style-cast -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough)
if(RONDO_WERROR)
  target_compile_options(rondo_build_flags INTERFACE -Werror)
endif()
if(RONDO_SANITIZE)
  target_compile_options(rondo_build_flags INTERFACE
    -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
  target_link_options(rondo_build_flags INTERFACE -fsanitize=address,undefined)
  # GCC's manual warns that sanitizers raise the rate of false -Wmaybe-uninitialized warnings; with
  # optimisation, GCC 12 gives them inside libstdc++'s <regex> (used by cpp-httplib). The normal
  # build keeps the warning.
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    target_compile_options(rondo_build_flags INTERFACE -Wno-maybe-uninitialized)
  endif()
endif()
if(RONDO_SANITIZE_THREAD)
  target_compile_options(rondo_build_flags INTERFACE -fsanitize=thread -fno-omit-frame-pointer)
  target_link_options(rondo_build_flags INTERFACE -fsanitize=thread)
endif()
if(RONDO_FUZZ)
  target_compile_options(rondo_build_flags INTERFACE -fsanitize=fuzzer-no-link,address,undefined)
  target_link_options(rondo_build_flags INTERFACE -fsanitize=address,undefined)
endif()

# rondo_module(NAME SOURCES... DEPS...): one library per module folder, aliased rondo::NAME,
# with the public headers under include/rondo/NAME/.
function(rondo_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(rondo_${name} STATIC ${ARG_SOURCES})
  add_library(rondo::${name} ALIAS rondo_${name})
  target_include_directories(rondo_${name}
    PUBLIC ${PROJECT_SOURCE_DIR}/include
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR})
  target_link_libraries(rondo_${name} PUBLIC ${ARG_DEPS} PRIVATE rondo_build_flags ${ARG_PRIVATE_DEPS})
endfunction()
