# vt_shaders(<target> <glsl files...>): compiles each GLSL file to SPIR-V at build time with
# glslangValidator and embeds it as a uint32 array in a generated header, so binaries need no
# shader files at run time. `mesh.vert` becomes <shaders/mesh_vert.h> defining kMeshVert.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(vt_shaders target)
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/generated)
  set(headers)
  set(includes)
  foreach(src ${ARGN})
    get_filename_component(dir ${src} DIRECTORY)
    file(GLOB glsl_includes CONFIGURE_DEPENDS ${dir}/*.glsl)   # shared #include files
    list(APPEND includes ${glsl_includes})
  endforeach()
  list(REMOVE_DUPLICATES includes)
  foreach(src ${ARGN})
    get_filename_component(name ${src} NAME)          # mesh.vert
    string(REPLACE "." "_" stem ${name})               # mesh_vert
    string(REPLACE "_" ";" parts ${stem})
    set(var "k")
    foreach(part ${parts})                             # kMeshVert
      string(SUBSTRING ${part} 0 1 first)
      string(SUBSTRING ${part} 1 -1 rest)
      string(TOUPPER ${first} first)
      string(APPEND var ${first}${rest})
    endforeach()
    set(header ${out_dir}/shaders/${stem}.h)
    add_custom_command(
      OUTPUT ${header}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${out_dir}/shaders
      COMMAND ${GLSLANG_VALIDATOR} -V --target-env vulkan1.1 --quiet --vn ${var} -o ${header} ${src}
      DEPENDS ${src} ${includes}
      COMMENT "glslang: ${name} -> SPIR-V"
      VERBATIM)
    list(APPEND headers ${header})
  endforeach()
  target_sources(${target} PRIVATE ${headers})
  target_include_directories(${target} PRIVATE ${out_dir})
endfunction()
