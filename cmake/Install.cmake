# The installed layout engine/core/paths.hpp expects, and the build tree's copy of it.
#
#   <prefix>/bin/bounce
#   <prefix>/share/bounce/shaders/   compiled SPIR-V, same tree as <build>/shaders
#   <prefix>/share/bounce/content/   levels, captures, glTF sources
#   <prefix>/share/bounce/tools/     plot_accuracy.py
#   <prefix>/share/doc/bounce/README.md
#
# paths.hpp derives share/bounce from the executable's folder, so these destinations are fixed
# (not GNUInstallDirs variables, which a packager could point elsewhere).

# The build tree links content/ and tools/ from the source tree, so a binary in it finds them the
# way an installed one does, with no source path compiled in.
foreach(dir content tools)
  if(NOT EXISTS ${PROJECT_BINARY_DIR}/${dir})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${dir} ${PROJECT_BINARY_DIR}/${dir} SYMBOLIC)
  endif()
endforeach()

install(TARGETS bounce RUNTIME DESTINATION bin)
install(DIRECTORY ${PROJECT_BINARY_DIR}/shaders/ DESTINATION share/bounce/shaders FILES_MATCHING PATTERN "*.spv")
install(DIRECTORY content/ DESTINATION share/bounce/content)
install(DIRECTORY tools/ DESTINATION share/bounce/tools USE_SOURCE_PERMISSIONS)
install(FILES README.md DESTINATION share/doc/bounce)
