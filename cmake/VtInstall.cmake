# Every install rule in one place. `cmake --install build [--prefix DIR]` puts under the prefix:
#   bin/vtouching                               the application
#   lib/vtouching/libxrsim.so                   the headless OpenXR runtime (tools/xrsim) and
#   share/vtouching/xrsim/xrsim.json            its manifest (XR_RUNTIME_JSON=...; relative path)
#   share/vtouching/assets/                     default scene, trajectories, xrsim scripts
#   share/doc/vtouching/                        README.md and docs/
#   share/man/man1/vtouching.1                  generated from the option table
#   share/bash-completion/completions/vtouching generated from the option table
# The target `installable` builds exactly what these rules need (scripts/run.sh builds it, then
# installs). A new installed part is one rule here plus, for a built target, add_dependencies.
include(GNUInstallDirs)
add_custom_target(installable)

# The application, its man page and completion script (the binary prints both).
install(TARGETS vtouching RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
set(vt_generated ${CMAKE_BINARY_DIR}/generated)
add_custom_command(OUTPUT ${vt_generated}/vtouching.1 ${vt_generated}/vtouching.bash-completion
                   COMMAND ${CMAKE_COMMAND} -E make_directory ${vt_generated}
                   COMMAND ${CMAKE_COMMAND} -DOUTPUT=${vt_generated}/vtouching.1 -P
                           ${PROJECT_SOURCE_DIR}/cmake/command_output.cmake -- $<TARGET_FILE:vtouching> help --man
                   COMMAND ${CMAKE_COMMAND} -DOUTPUT=${vt_generated}/vtouching.bash-completion -P
                           ${PROJECT_SOURCE_DIR}/cmake/command_output.cmake -- $<TARGET_FILE:vtouching> completion bash
                   DEPENDS vtouching ${PROJECT_SOURCE_DIR}/cmake/command_output.cmake
                   COMMENT "vtouching: man page and bash completion from the option table" VERBATIM)
add_custom_target(vt_manual ALL DEPENDS ${vt_generated}/vtouching.1 ${vt_generated}/vtouching.bash-completion)
install(FILES ${vt_generated}/vtouching.1 DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
install(FILES ${vt_generated}/vtouching.bash-completion DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
        RENAME vtouching)
add_dependencies(installable vtouching vt_manual)

# The headless OpenXR runtime; its manifest names the library relative to itself, so the
# installed tree works under any prefix.
if(TARGET xrsim)
  set(vt_xrsim_manifest_dir ${CMAKE_INSTALL_DATADIR}/vtouching/xrsim)
  file(RELATIVE_PATH vt_xrsim_library /${vt_xrsim_manifest_dir} /${CMAKE_INSTALL_LIBDIR}/vtouching/libxrsim.so)
  file(GENERATE OUTPUT ${vt_generated}/xrsim.json CONTENT
"{
  \"file_format_version\": \"1.0.0\",
  \"runtime\": {
    \"name\": \"xrsim (V-Touching headless runtime)\",
    \"library_path\": \"${vt_xrsim_library}\"
  }
}
")
  install(TARGETS xrsim LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}/vtouching)
  install(FILES ${vt_generated}/xrsim.json DESTINATION ${vt_xrsim_manifest_dir})
  add_dependencies(installable xrsim)
endif()

# Data and documentation.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/assets/ DESTINATION ${CMAKE_INSTALL_DATADIR}/vtouching/assets)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)

# The Python module (its install rules are in python/CMakeLists.txt).
if(TARGET vt_python)
  add_dependencies(installable vt_python)
endif()
