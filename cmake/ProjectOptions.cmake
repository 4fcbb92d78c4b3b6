# Compile options shared by every project target: warnings as errors, optional sanitizers.
add_library(vegstream_options INTERFACE)
# -Wno-missing-field-initializers: Vulkan's C structs are filled with the idiom
# `VkXxxCreateInfo ci{VK_STRUCTURE_TYPE_...};` whose other members are zero by the language rules.
# -Wno-restrict: GCC 12 at -O3 reports a false overlap in std::string concatenation
# (GCC bug 105651) for ordinary code like `"literal" + s`.
target_compile_options(vegstream_options INTERFACE
  -Wall -Wextra -Wshadow -Wconversion -Werror -Wno-missing-field-initializers)
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  target_compile_options(vegstream_options INTERFACE -Wno-restrict)
endif()
# The libFuzzer build (VEGSTREAM_FUZZ, clang): every project library instrumented for coverage
# and checked by ASan + UBSan (an UB report aborts, so libFuzzer keeps the input). Warnings stay
# on but are not errors there: clang warns about things GCC does not, and the GCC build is the
# one that keeps the code warning-free.
if(VEGSTREAM_FUZZ)
  target_compile_options(vegstream_options INTERFACE
    -Wno-error -fsanitize=fuzzer-no-link,address,undefined -fno-sanitize-recover=undefined -fno-omit-frame-pointer -g)
  target_link_options(vegstream_options INTERFACE -fsanitize=address,undefined)
endif()
target_compile_definitions(vegstream_options INTERFACE
  GLM_FORCE_DEPTH_ZERO_TO_ONE GLM_FORCE_RADIANS)
if(VEGSTREAM_SANITIZE)
  target_compile_options(vegstream_options INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  target_link_options(vegstream_options INTERFACE -fsanitize=address,undefined)
endif()

# The folders whose libraries also compile with -Wpedantic -Wsign-conversion (issue 43 item 4:
# "where they can be clean"): every library below render/ in the folder order. render/, scene/ and
# app/ are not yet (Vulkan's and ImGui's C interfaces take int and uint32_t in the same calls).
set(VEGSTREAM_STRICT_FOLDERS core geo datasets streaming terrain vegetation simulation flight)

# vegstream_add_library(NAME SOURCES... DEPS ...): one library per folder, with the folder's
# parent as include root so code writes #include "core/result.h".
function(vegstream_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  if(ARG_SOURCES)
    add_library(${name} STATIC ${ARG_SOURCES})
    target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE vegstream_options ${ARG_PRIVATE_DEPS})
    get_filename_component(folder ${CMAKE_CURRENT_SOURCE_DIR} NAME)
    if(folder IN_LIST VEGSTREAM_STRICT_FOLDERS AND NOT VEGSTREAM_FUZZ)
      target_compile_options(${name} PRIVATE -Wpedantic -Wsign-conversion)
    endif()
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} INTERFACE ${ARG_PUBLIC_DEPS})
  endif()
endfunction()
