#pragma once
/// A scene object's faces as validated polygons, an OBJ's faces with the materials of its
/// libraries (mtl.h), and a mesh file alone as a scene (`radiosity info room.obj`).
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "scene/input_files.h"
#include "scene/mesh_reader.h"
#include "scene/scene.h"

namespace rad {

/// The materials a scene took from material libraries, by library path and name, so that
/// objects sharing a library share its materials; and the grey default, once added.
struct LibraryMaterials {
  std::map<std::pair<std::string, std::string>, int> index;
  int grey = -1;
};

/// The scene material of each face of an OBJ (`use`, as read_mesh_faces gives it for the mesh
/// file `mesh`): the material its `usemtl` names, the scene file's own of that name if it has
/// one (`named`: name to index in scene.materials; DESIGN.md §5), else from the `mtllib`
/// libraries (paths relative to the mesh's folder), added to scene.materials once per library
/// and name. Faces that name no
/// material, or one that no library holds, and the faces of a library that cannot be opened,
/// take a grey default (reflectance 0.5) with a warning each. A library that opens but is
/// malformed throws InputError naming its line. `where` names the object in messages.
std::vector<int> obj_face_materials(const MeshMaterials& use, const std::filesystem::path& mesh,
                                    const std::string& where,
                                    const std::map<std::string, int>& named, Scene& scene,
                                    LibraryMaterials& added, InputFiles* files);

/// The material every face has, or -1 when they have several (SceneObject::material).
int common_material(const std::vector<int>& face_material);

/// Validates `faces` (make_polygons) into scene.polygons as the polygons of object `object`,
/// face f with material face_material[f]; messages name it "WHERE face F" when `from_mesh`,
/// else "WHERE polygon F" ("scene.json: objects[1] (room.obj) face 4"). With `flip`, each
/// face's vertex order is reversed first, which turns its front side. A mesh's faces that hold
/// no area (holds_no_area: exporters write them) are left out with one warning; an inline
/// polygon that holds none is refused. Throws InputError for a face validation refuses and past the
/// scene's polygon limit.
void add_object_faces(std::vector<std::vector<Vec3>> faces, const std::vector<int>& face_material,
                      const std::string& where, bool from_mesh, int object, bool flip,
                      Scene& scene);

/// A camera that shows a scene that has none: from inside when the middle of its bounds is a
/// room's (a ray along each axis meets a polygon's front: a solid's middle meets backs), near
/// the +z wall looking at the middle, 60 degrees; else from outside, back along (0.5, 0.4, 1) far
/// enough that the bounds' sphere fills a 40 degree view. Up is +y, the convention of OBJ
/// exporters.
CameraSpec camera_from_bounds(const Scene& scene);

/// A mesh file alone as a scene: one object of all its faces, an OBJ's with the materials of
/// its libraries (others, and an OBJ that names none, grey with a warning), and
/// camera_from_bounds. Throws InputError as a scene file's mesh object does.
Scene mesh_scene(const std::filesystem::path& file, InputFiles* files, bool flip);

}  // namespace rad
