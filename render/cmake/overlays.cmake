# The 3D overlays (render/src/overlay_catalogue.cpp, overlay_obj_file.cpp, overlay_texture_file.cpp):
# the catalogue is TOML, the meshes Wavefront OBJ (tinyobjloader), the textures PNG (libpng).
# Include after add_subdirectory(render).
find_package(tinyobjloader REQUIRED)
target_link_libraries(render PRIVATE tinyobjloader::tinyobjloader PkgConfig::TOMLPP PkgConfig::PNG)
# mirror-bench's overlay case (bench/overlay_render_case.cpp) draws with the renderer.
if(TARGET mirror-bench)
  target_link_libraries(mirror-bench PRIVATE render PkgConfig::EGL)
endif()
