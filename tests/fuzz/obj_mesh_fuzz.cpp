// An overlay mesh (Wavefront OBJ): read with its values checked, indexed and, when closed, turned
// outward, as the catalogue does. The input's size picks the objects asked for and whether a
// texture (so `vt` on every face) is needed, so the seeds stay the real OBJ files.
#include "fuzz_input.hpp"
#include "overlay_obj_file.hpp"  // private to render/src

#include <stdexcept>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    const bool needUv = size % 2 == 1;
    std::vector<std::string> objects;
    if (size % 4 >= 2)
        objects = {"crown", "lenses"};
    const std::string path = fuzz::writeScratchFile("mesh.obj", data, size);
    try {
        const auto triangles = render::readObjTriangles(path, "mesh.obj", objects, needUv);
        render::OverlayMesh mesh;
        render::indexTriangles(triangles, mesh, "mesh.obj");
        (void)render::orientClosedMesh(mesh);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
