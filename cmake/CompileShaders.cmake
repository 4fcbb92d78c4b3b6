# GLSL → SPIR-V at build time with glslangValidator. Each shader becomes a C header holding a
# uint32_t array (glslangValidator --vn), so the binary carries its shaders and no .spv file
# needs to be found at run time or kept in git. Includes from shaders/common/ are tracked
# through glslangValidator's depfile, so editing a shared file rebuilds its users.
function(vegstream_compile_shaders target)
  cmake_parse_arguments(ARG "" "" "SOURCES" ${ARGN})
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated/shaders)
  file(MAKE_DIRECTORY ${out_dir})
  set(headers)
  foreach(src ${ARG_SOURCES})
    get_filename_component(abs ${src} ABSOLUTE)
    get_filename_component(fname ${src} NAME)
    string(REGEX REPLACE "[^A-Za-z0-9]" "_" var "${fname}")
    set(hdr ${out_dir}/${fname}.h)
    add_custom_command(
      OUTPUT ${hdr}
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.2 -g0
              -I${CMAKE_CURRENT_SOURCE_DIR}/common -I${PROJECT_SOURCE_DIR} --vn spv_${var}
              --depfile ${hdr}.d -o ${hdr} ${abs}
      DEPENDS ${abs}
      DEPFILE ${hdr}.d
      COMMENT "glslang ${fname}"
      VERBATIM)
    list(APPEND headers ${hdr})
  endforeach()
  add_custom_target(${target}_spirv DEPENDS ${headers})
  add_library(${target} INTERFACE)
  add_dependencies(${target} ${target}_spirv)
  target_include_directories(${target} INTERFACE ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set_property(TARGET ${target} PROPERTY VEGSTREAM_SPIRV_HEADERS "${headers}")
endfunction()
