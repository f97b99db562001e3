#pragma once
// Reading an overlay mesh from a Wavefront OBJ file (assets/overlays/FORMAT.md): the file read
// bounded (vision::readBoundedFile), its values checked (finite, indices in range, at least one
// triangle with area), equal vertices shared, closed pieces turned outward. Each function throws
// std::runtime_error with one line ("OBJ NAME: why"); the catalogue adds where it was named.
// Private to the overlay catalogue.

#include "render/overlay_catalogue.hpp"

#include <string>
#include <vector>

namespace render {

/// The triangles (3 vertices each) of the objects or groups `objects` (all when empty) of the OBJ
/// at `path`, shown as `shownPath` in errors, with flat normals where the file gives none.
/// `needUv`: every face must have texture coordinates (the mesh has a texture).
std::vector<OverlayVertex> readObjTriangles(const std::string& path, const std::string& shownPath,
                                            const std::vector<std::string>& objects, bool needUv);

/// Shares equal vertices between triangles (GL then shades each once: llvmpipe caches indexed
/// vertices) and makes the 16-bit index list GLES2 draws.
void indexTriangles(const std::vector<OverlayVertex>& triangles, OverlayMesh& mesh,
                    const std::string& shownPath);

/// True when the mesh is closed (every edge, by position, shared by exactly two triangles that
/// run it in opposite directions), after turning each closed piece counter-clockwise seen from
/// outside (positive volume): its back faces can then be culled, which halves the triangles
/// software GL rasterises. False (mesh unchanged) for open surfaces such as a lens or a brim.
bool orientClosedMesh(OverlayMesh& mesh);

}  // namespace render
