// Every scene key of hydromodal, declared once: type, default, unit, range, meaning, and the
// stages whose artefacts depend on it (so a change reruns exactly those stages). The generated
// reference (`--print-config-reference`) and all validation come from this table.
#include "io/scene.hpp"

namespace hm::io {
namespace {

constexpr double inf = 1e300;
const std::vector<std::string> mesh_stage{"fsi-mesh"};
const std::vector<std::string> modes_stage{"fsi-modes"};
const std::vector<std::string> map_stage{"fsi-map"};

KeyDecl number(std::string path, std::string def, std::string unit, double min, double max,
               std::string doc, std::vector<std::string> stages, bool min_excl = false,
               bool max_excl = false) {
  KeyDecl d;
  d.path = std::move(path);
  d.type = KeyType::number;
  d.default_text = std::move(def);
  d.unit = std::move(unit);
  d.min = min;
  d.max = max;
  d.min_exclusive = min_excl;
  d.max_exclusive = max_excl;
  d.doc = std::move(doc);
  d.stages = std::move(stages);
  return d;
}

KeyDecl integer(std::string path, std::string def, double min, double max, std::string doc,
                std::vector<std::string> stages) {
  KeyDecl d =
      number(std::move(path), std::move(def), "1", min, max, std::move(doc), std::move(stages));
  d.type = KeyType::integer;
  return d;
}

KeyDecl text(std::string path, std::string def, std::vector<std::string> choices, std::string doc,
             std::vector<std::string> stages) {
  KeyDecl d;
  d.path = std::move(path);
  d.type = KeyType::string;
  d.default_text = std::move(def);
  d.choices = std::move(choices);
  d.doc = std::move(doc);
  d.stages = std::move(stages);
  return d;
}

KeyDecl vector(std::string path, std::string def, std::string unit, int size, std::string doc,
               std::vector<std::string> stages, double min = -inf, double max = inf) {
  KeyDecl d = number(std::move(path), std::move(def), std::move(unit), min, max, std::move(doc),
                     std::move(stages));
  d.type = KeyType::vector;
  d.vector_size = size;
  return d;
}

KeyDecl string_list(std::string path, std::string def, std::vector<std::string> choices,
                    std::string doc, std::vector<std::string> stages) {
  KeyDecl d =
      text(std::move(path), std::move(def), std::move(choices), std::move(doc), std::move(stages));
  d.type = KeyType::string_list;
  return d;
}

KeyDecl boolean(std::string path, std::string def, std::string doc,
                std::vector<std::string> stages) {
  KeyDecl d = text(std::move(path), std::move(def), {}, std::move(doc), std::move(stages));
  d.type = KeyType::boolean;
  return d;
}

}  // namespace

const std::vector<SectionDecl>& scene_sections() {
  static const std::vector<SectionDecl> sections{
      {"case", true, "What the case is."},
      {"structure", false,
       "The elastic structure (omit for rigid-only scenes: the structure stages are skipped)."},
      {"structure.geometry", true, "Where the structure's shape comes from."},
      {"structure.mesh", true, "Finite-element mesh of the structure (quadratic elements)."},
      {"structure.group[]", false,
       "Named boundary groups selected by an axis-aligned box (e.g. `clamped`, `wetted`); every "
       "boundary node/facet inside the box belongs to the group. Primitives also have the groups "
       "xmin, xmax, ymin, ymax (, zmin, zmax); .geo files bring their own physical groups."},
      {"structure.refine[]", false,
       "Smaller mesh sizes near named groups (a primitive's face, a .geo physical group or a box "
       "group); gmsh grades the size away from them."},
      {"structure.material", true, "Linear isotropic elastic material."},
      {"wall[]", false,
       "Rigid fluid walls as surface meshes (segments in 2-D, triangles in 3-D, normals into the "
       "fluid), meshed by fsi-mesh into mesh.h5 under /walls/<name>."},
      {"modes", false, "Mode extraction (fsi-modes)."},
      {"map", false, "Mapping of the mode shapes onto the surface the fluid sees (fsi-map)."},
  };
  return sections;
}

const std::vector<KeyDecl>& scene_keys() {
  static const std::vector<KeyDecl> keys{
      // [case]
      text("case.name", "", {}, "case name, used in reports", {}),
      integer("case.dimension", "", 2, 3, "2 for plane (x, y) cases, 3 for spatial ones",
              {"fsi-mesh", "fsi-modes"}),
      text("case.description", "\"\"", {}, "free text for reports", {}),

      // [structure.geometry]
      text("structure.geometry.kind", "", {"rectangle", "box", "file"},
           "rectangle (2-D) or box (3-D) primitive given by origin and size, or a geometry file",
           mesh_stage),
      text("structure.geometry.file", "\"\"", {},
           "geometry file for kind = \"file\", relative to the scene: .geo (gmsh script), "
           ".step/.stp/.brep/.iges/.igs (CAD), .stl/.obj/.ply (closed surface mesh)",
           mesh_stage),
      vector("structure.geometry.origin", "[]", "m", 0,
             "lowest corner of the rectangle/box primitive (required for those kinds)", mesh_stage),
      vector("structure.geometry.size", "[]", "m", 0,
             "edge lengths of the rectangle/box primitive (required for those kinds)", mesh_stage,
             0.0),

      // [structure.mesh]
      number("structure.mesh.size", "", "m", 0, inf, "target element edge length", mesh_stage,
             true),
      number("structure.mesh.min_quality", "0.1", "1", 0, 1,
             "elements below this shape quality are reported as slivers", mesh_stage),

      // [[structure.refine]]
      text("structure.refine[].group", "", {}, "name of the group to refine near", mesh_stage),
      number("structure.refine[].size", "", "m", 0, inf,
             "target element size at the group (below structure.mesh.size)", mesh_stage, true),

      // [[structure.group]]
      text("structure.group[].name", "", {}, "group name (referenced by other keys)", mesh_stage),
      vector("structure.group[].min", "", "m", 0, "lower corner of the selection box", mesh_stage),
      vector("structure.group[].max", "", "m", 0, "upper corner of the selection box", mesh_stage),

      // [[wall]]
      text("wall[].name", "", {}, "wall name (a dataset group /walls/<name> of mesh.h5)",
           mesh_stage),
      text("wall[].kind", "", {"rectangle", "box", "file"},
           "the inside of a rectangle (2-D) or box (3-D) tank given by origin and size, or a "
           "surface file (.stl, .obj, .ply; or .geo curves/surfaces)",
           mesh_stage),
      vector("wall[].origin", "[]", "m", 0, "lowest corner of the tank primitive", mesh_stage),
      vector("wall[].size", "[]", "m", 0, "edge lengths of the tank primitive", mesh_stage, 0.0),
      string_list("wall[].faces", "[]", {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"},
                  "faces of the primitive to keep (empty: all; an open-top tank omits ymax/zmax)",
                  mesh_stage),
      text("wall[].file", "\"\"", {}, "surface file for kind = \"file\", relative to the scene",
           mesh_stage),
      number("wall[].mesh_size", "", "m", 0, inf, "target edge length of the wall mesh", mesh_stage,
             true),
      boolean("wall[].flip_normals", "false",
              "reverse the normals of a file wall whose fluid side is the other one", mesh_stage),

      // [structure]
      text("structure.formulation", "\"plane_strain\"", {"plane_strain", "plane_stress"},
           "2-D only: plane strain (thick in z) or plane stress (thin plate in its plane)",
           modes_stage),
      number("structure.thickness", "1.0", "m", 0, inf,
             "2-D only: out-of-plane thickness the 2-D mass and stiffness are multiplied by",
             modes_stage, true),
      text("structure.clamped", "\"\"", {},
           "name of the group whose nodes are fixed (all displacement components); empty: the "
           "structure is free-free",
           modes_stage),

      // [structure.material]
      number("structure.material.youngs_modulus", "", "Pa", 0, inf, "Young's modulus E",
             modes_stage, true),
      number("structure.material.poisson_ratio", "", "1", -1, 0.5, "Poisson's ratio nu",
             modes_stage, true, true),
      number("structure.material.density", "", "kg/m^3", 0, inf, "mass density rho", modes_stage,
             true),

      // [modes]
      integer("modes.count", "10", 1, 100000,
              "number of lowest modes to extract (with max_frequency_hz: the most to return)",
              modes_stage),
      number("modes.max_frequency_hz", "0.0", "Hz", 0, inf,
             "when > 0, extract every mode below this frequency (up to modes.count)", modes_stage),
      number("modes.damping_ratio", "0.0", "1", 0, inf,
             "modal damping ratio zeta added to every mode", modes_stage),
      vector("modes.damping_ratios", "[]", "1", -1,
             "damping ratio of each mode, lowest first (instead of modes.damping_ratio; as many "
             "values as modes are extracted)",
             modes_stage, 0.0),
      number("modes.rayleigh_alpha", "0.0", "1/s", 0, inf,
             "Rayleigh mass-proportional damping: zeta_i += alpha / (2 omega_i)", modes_stage),
      number("modes.rayleigh_beta", "0.0", "s", 0, inf,
             "Rayleigh stiffness-proportional damping: zeta_i += beta omega_i / 2", modes_stage),
      vector("modes.reference_point", "[]", "m", 0,
             "point the rotational participation factors refer to (default: the origin)",
             modes_stage),
      text("modes.solver", "\"arpack\"", {"arpack", "spectra", "dense"},
           "eigensolver: ARPACK shift-invert Lanczos; Spectra (same operator); dense LAPACK-style "
           "(small models only)",
           modes_stage),
      number("modes.tolerance", "1e-12", "1", 0, 1e-3,
             "relative convergence tolerance of the Lanczos iteration", modes_stage, true),
      integer("modes.max_restarts", "1000", 1, 1000000,
              "implicit restarts of the Lanczos iteration before it gives up (exit code 3)",
              modes_stage),

      // [map]
      text("map.target", "\"surface\"", {"surface", "file"},
           "surface: the structure's own boundary surface (optionally refined to map.max_edge); "
           "file: the surface mesh in map.file",
           map_stage),
      text("map.file", "\"\"", {},
           "target surface mesh for map.target = \"file\" (.stl, .obj, .ply; metres), relative to "
           "the scene",
           map_stage),
      number("map.max_edge", "0.0", "m", 0, inf,
             "when > 0, the target surface is refined until no edge is longer (the fluid's "
             "resolution)",
             map_stage),
      number("map.support_factor", "6.0", "1", 1, 100,
             "RBF support radius in mean source node spacings (4: ~2e-3 relative interpolation "
             "error on smooth fields, 6: ~3e-4, 8: ~6e-5; measured in tests/rbf)",
             map_stage),
      number("map.support_radius", "0.0", "m", 0, inf,
             "when > 0, a fixed RBF support radius instead of map.support_factor", map_stage),
      number("map.far_factor", "2.0", "1", 0, inf,
             "target vertices farther than this many source spacings from the structure's "
             "surface nodes are an error",
             map_stage, true),
  };
  return keys;
}

}  // namespace hm::io
