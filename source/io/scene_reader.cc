#include <talus/scene/scene.h>

#include <talus/io/file_output.h>
#include <talus/io/scene_checks.h>
#include <talus/zone/block_mesher.h>

#include "joint_materials_reader.h"
#include "rock_materials_reader.h"
#include "parameter_file.h"
#include "region_reader.h"
#include "stage_reader.h"
#include "time_function_reader.h"
#include "water_reader.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include <algorithm>
#include <filesystem>
#include <limits>
#include <regex>
#include <tuple>

namespace talus
{

namespace
{

namespace P = dealii::Patterns;

/// Numbered subsections a file may have (ParameterHandler's declarations
/// take time in the square of their number).
constexpr std::size_t max_numbered_sections = 10000;
/// Sides of the brick (m) whose cuts double precision handles.
constexpr double min_brick_side = 1e-6, max_brick_side = 1e8;
/// kg/m^3: no material is denser than this (osmium: 22,590).
constexpr double max_density = 1e5;

const std::string vec3_allowed = "three numbers separated by commas, e.g. 0, 0, 0";

P::List vec3_pattern()
{
  return P::List(P::Double(), 3, 3, ",");
}

/// Reads "Corner min"/"Corner max" of the current subsection as a box and
/// checks that it has positive size in every direction.
Box read_box(const ParameterFile& prm, const std::string& lo_name, const std::string& hi_name)
{
  Box b{prm.get_vec3(lo_name), prm.get_vec3(hi_name)};
  for (unsigned int d = 0; d < 3; ++d)
    if (!(b.hi[d] > b.lo[d]))
      throw prm.error(hi_name, "must exceed '" + lo_name + "' in every coordinate",
                      "a box with hi > lo in x, y and z");
  return b;
}

void declare_box(ParameterFile& prm, const std::string& lo_name, const std::string& hi_name,
                 const std::string& what)
{
  prm.declare(lo_name, "0, 0, 0", vec3_pattern(), vec3_allowed, "Lower corner (m) of " + what);
  prm.declare(hi_name, "1, 1, 1", vec3_pattern(), vec3_allowed, "Upper corner (m) of " + what);
}

// ---- Model: the starting brick and how it is cut -------------------------

void declare_model(ParameterFile& prm)
{
  prm.enter("Model");
  declare_box(prm, "Brick min", "Brick max", "the brick all blocks are cut from");
  prm.declare("Default group", "rock", P::Anything(), "any name",
              "Group of blocks that no 'Group N' region selects.");
  prm.declare("Cutting tolerance", "1e-9", P::Double(0.0, 1e-3), "a number in [0, 1e-3]",
              "Vertices closer to a cutting plane than this times the block size lie on it.");
  prm.declare("Minimum block volume", "auto", P::Anything(),
              "auto, or a number >= 0 (m^3)",
              "A cut that would leave a smaller piece is not made, and is reported. auto: 1e-7 "
              "of the brick's volume (a sliver that small would set the time step of the whole "
              "model); 0: every cut is made.");
  prm.leave();
}

void parse_model(ParameterFile& prm, Scene& scene)
{
  prm.enter("Model");
  scene.brick = read_box(prm, "Brick min", "Brick max");
  // Cutting planes, volumes and the cutting tolerance need the sides and
  // their cubes well inside double precision.
  const Vec3 sides = scene.brick.hi - scene.brick.lo;
  if (!(sides.minCoeff() >= min_brick_side && sides.maxCoeff() <= max_brick_side))
    throw prm.error("Brick max",
                    "makes a brick of sides " + number(sides[0]) + ", " + number(sides[1]) + ", " +
                        number(sides[2]) + " m, which double precision cannot cut reliably",
                    "a brick whose sides are from 1e-6 to 1e8 m");
  scene.default_group = prm.get("Default group");
  scene.cutting.relative_tolerance = prm.get_double("Cutting tolerance");
  const std::string minimum = prm.get("Minimum block volume");
  if (minimum == "auto")
    scene.cutting.minimum_volume = relative_minimum_block_volume * sides.prod();
  else
  {
    char* end = nullptr;
    scene.cutting.minimum_volume = std::strtod(minimum.c_str(), &end);
    while (end != nullptr && *end == ' ')
      ++end;
    if (minimum.empty() || end == nullptr || *end != '\0' ||
        !(scene.cutting.minimum_volume >= 0.0) || !std::isfinite(scene.cutting.minimum_volume))
      throw prm.error("Minimum block volume", "'" + minimum + "' is not auto or a number >= 0",
                      "auto, or a number >= 0 (m^3)");
  }
  prm.leave();
}

// ---- Material ------------------------------------------------------------

void declare_material(ParameterFile& prm)
{
  prm.enter("Material");
  prm.declare("Density", "2600", P::Double(), "a number > 0 and at most 1e5 (kg/m^3)",
              "Rock density (kg/m^3).");
  prm.leave();
}

void parse_material(ParameterFile& prm, Scene& scene)
{
  prm.enter("Material");
  scene.density = prm.get_double("Density");
  if (!(scene.density > 0.0))
    throw prm.error("Density", "must be positive", "a number > 0 and at most 1e5 (kg/m^3)");
  // Far beyond any rock (osmium, the densest element, is 22,590 kg/m^3): the
  // automatic time step grows with the mass and the joints cannot carry it.
  if (scene.density > max_density)
    throw prm.error("Density", "is denser than any material (" + number(scene.density) + " kg/m^3)",
                    "a number > 0 and at most 1e5 (kg/m^3)");
  prm.leave();
}

// ---- Joint sets and single joints ------------------------------------------

void declare_orientation(ParameterFile& prm)
{
  prm.declare("Dip", "0", P::Double(0.0, 90.0), "a number from 0 to 90 (degrees)",
              "Dip angle of the joint plane from horizontal (degrees).");
  prm.declare("Dip direction", "0", P::Double(0.0, 360.0), "a number from 0 to 360 (degrees)",
              "Azimuth of the down-dip line, clockwise from north (+y), degrees.");
  prm.declare("Origin", "0, 0, 0", vec3_pattern(), vec3_allowed, "A point on the plane (m).");
  prm.declare("Limit to extent", "false", P::Bool(), "true or false",
              "Cut only blocks whose centroid lies in the extent box.");
  declare_box(prm, "Extent min", "Extent max", "the region the joints cut");
}

void declare_joint_set(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  declare_orientation(prm);
  declare_joint_material_entry(prm);
  prm.declare("Spacing", "1", P::Double(), "a number > 0 (m)",
              "Normal distance between neighbouring joints of the set (m).");
  prm.declare("Number of joints", "0", P::Integer(0, 1000000000),
              "an integer from 0 to 1e9 (0: unlimited)",
              "Joints from the one through Origin along the upward normal; 0 fills the model.");
  prm.leave();
}

void declare_joint(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  declare_orientation(prm);
  declare_joint_material_entry(prm);
  prm.leave();
}

template <typename Spec>
void parse_orientation(ParameterFile& prm, Spec& spec)
{
  spec.dip = prm.get_double("Dip");
  spec.dip_direction = prm.get_double("Dip direction");
  spec.origin = prm.get_vec3("Origin");
  spec.limited = prm.get_bool("Limit to extent");
  if (spec.limited)
    spec.extent = read_box(prm, "Extent min", "Extent max");
}

JointSetSpec parse_joint_set(ParameterFile& prm, const std::string& section, Scene& scene)
{
  prm.enter(section);
  scene.solver.joint_rule.of_joint_set.push_back(parse_joint_material_entry(prm, scene));
  JointSetSpec set;
  parse_orientation(prm, set);
  set.spacing = prm.get_double("Spacing");
  if (!(set.spacing > 0.0))
    throw prm.error("Spacing", "must be positive", "a number > 0 (m)");
  set.count = static_cast<unsigned int>(prm.get_integer("Number of joints"));
  prm.leave();
  return set;
}

JointPlaneSpec parse_joint(ParameterFile& prm, const std::string& section, Scene& scene)
{
  prm.enter(section);
  scene.solver.joint_rule.of_joint.push_back(parse_joint_material_entry(prm, scene));
  JointPlaneSpec joint;
  parse_orientation(prm, joint);
  prm.leave();
  return joint;
}

// ---- Excavations -----------------------------------------------------------

void declare_excavation(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  declare_region(prm, "the region to remove");
  prm.leave();
}

ExcavationSpec parse_excavation(ParameterFile& prm, const std::string& section, const Scene& scene)
{
  prm.enter(section);
  ExcavationSpec e;
  std::string description;
  e.region = parse_region(prm, scene.brick, description);
  e.description = section + ": " + description;
  e.section = section;
  prm.leave();
  return e;
}

// ---- Groups ------------------------------------------------------------------

void declare_group(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  prm.declare("Name", "group", P::Anything(), "any name", "Name given to the selected blocks.");
  declare_region(prm, "the region whose blocks join the group");
  prm.declare("Blocks", "", P::List(P::Integer(0, 2000000000)), "block numbers separated by commas",
              "These blocks (numbers as built, as the blocks' VTU shows them) join the group "
              "instead of those of the region.");
  prm.declare("Side of joint", "", P::Anything(), "'Joint N' or 'Joint set N' of the file, or empty",
              "Only the blocks on one side of this joint's plane join (with a 'Shape' set: "
              "those in the region and on that side): a fault's hanging wall or footwall.");
  prm.declare("Joint index", "0", P::Integer(-1000000000, 1000000000), "an integer",
              "A joint set's joint: 0 the one through its 'Origin', k the one k spacings along "
              "its normal (negative: the other way).");
  prm.declare("Side", "above", P::Selection("above|below"), "above or below",
              "above: the side the joint's normal points to (up; for a vertical joint, its dip "
              "direction); below: the other.");
  prm.leave();
}

GroupSpec parse_group(ParameterFile& prm, const std::string& section, const Scene& scene)
{
  prm.enter(section);
  std::string description;
  GroupSpec g;
  g.name = prm.get("Name");
  g.region = parse_region(prm, scene.brick, description);
  g.section = section;
  for (const std::string& b : dealii::Utilities::split_string_list(prm.get("Blocks")))
    g.blocks.push_back(static_cast<unsigned int>(std::stoul(b)));
  g.side_of = prm.get("Side of joint");
  g.joint_index = prm.get_integer("Joint index");
  g.above = prm.get("Side") == "above";
  if (!g.side_of.empty() && !g.blocks.empty())
    throw prm.error("Side of joint", "is given with 'Blocks', which names the blocks itself",
                    "either 'Blocks' or a region and 'Side of joint'");
  // Without a shape of its own, the side of the joint is the whole region.
  if (!g.side_of.empty() && !prm.is_set("Shape") && !prm.is_set("Corner min") &&
      !prm.is_set("Corner max"))
    g.region = ConvexRegion::box(scene.brick);
  prm.leave();
  return g;
}

/// The groups' 'Side of joint', once the joints are read: the half-space
/// on that side of the joint's plane cuts the group's region.
void apply_joint_sides(ParameterFile& prm, Scene& scene)
{
  for (GroupSpec& g : scene.groups)
  {
    if (g.side_of.empty())
      continue;
    prm.enter(g.section);
    const std::string allowed = "'Joint N' or 'Joint set N', a subsection of the file";
    Vec3 point, normal;
    const auto set =
        std::find(scene.joint_set_sections.begin(), scene.joint_set_sections.end(), g.side_of);
    const auto joint =
        std::find(scene.joint_plane_sections.begin(), scene.joint_plane_sections.end(), g.side_of);
    if (set != scene.joint_set_sections.end())
    {
      const JointSetSpec& j = scene.joint_sets[std::size_t(set - scene.joint_set_sections.begin())];
      normal = normal_from_dip(j.dip, j.dip_direction);
      point = j.origin + double(g.joint_index) * j.spacing * normal;
    }
    else if (joint != scene.joint_plane_sections.end())
    {
      const JointPlaneSpec& j =
          scene.joint_planes[std::size_t(joint - scene.joint_plane_sections.begin())];
      normal = normal_from_dip(j.dip, j.dip_direction);
      point = j.origin;
      if (g.joint_index != 0)
        throw prm.error("Joint index", "is for a joint set, and '" + g.side_of + "' is one joint",
                        "0 with a 'Joint N'");
    }
    else
      throw prm.error("Side of joint", "names '" + g.side_of + "', which is no subsection of the file",
                      allowed);
    const ConvexRegion side =
        ConvexRegion::half_space(point, g.above ? normal : Vec3(-normal), scene.brick);
    if (!(side.volume > 0.0))
      throw prm.error("Side of joint", "leaves no part of the brick on the '" +
                                           std::string(g.above ? "above" : "below") + "' side",
                      "a joint whose plane crosses the brick, and the side that holds rock");
    g.region.planes.insert(g.region.planes.end(), side.planes.begin(), side.planes.end());
    for (int d = 0; d < 3; ++d)
    {
      g.region.bounds.lo[d] = std::max(g.region.bounds.lo[d], side.bounds.lo[d]);
      g.region.bounds.hi[d] = std::min(g.region.bounds.hi[d], side.bounds.hi[d]);
    }
    g.region.is_box = false;
    g.region.volume = 0.0; // not known in closed form; groups do not need it
    prm.leave();
  }
}

} // namespace

/// Throws unless `name` is the default group or a 'Group N' name; `entry`
/// is the entry of the current subsection that names it.
void check_group_name(const ParameterFile& prm, const std::string& entry, const Scene& scene,
                      const std::string& name)
{
  bool known = name == scene.default_group;
  for (const GroupSpec& spec : scene.groups)
    known |= spec.name == name;
  if (!known)
    throw prm.error(entry, "names the unknown group '" + name + "'",
                    "the default group '" + scene.default_group + "' or a 'Group N' name");
}

namespace
{

// ---- Loads -------------------------------------------------------------------

void declare_load(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  prm.declare("Group", "", P::Anything(), "a group name", "Blocks this load acts on.");
  prm.declare("Force", "0, 0, 0", vec3_pattern(), vec3_allowed,
              "Force on each block of the group at its centroid (N).");
  prm.declare("Force rate", "0, 0, 0", vec3_pattern(), vec3_allowed,
              "Growth of that force per second of model time (N/s).");
  prm.declare("Prescribe velocity", "false", P::Bool(), "true or false",
              "Hold the blocks' velocity at 'Velocity' (they still rotate freely).");
  prm.declare("Velocity", "0, 0, 0", vec3_pattern(), vec3_allowed, "Prescribed velocity (m/s).");
  prm.declare("Held components", "x, y, z", P::MultipleSelection("x|y|z"),
              "some of x, y, z separated by commas",
              "Components of the velocity that are prescribed; the others stay free.");
  prm.declare("Hold rotation", "false", P::Bool(), "true or false",
              "The blocks do not rotate (like the platen of a shear box).");
  prm.declare("Initial velocity", "0, 0, 0", vec3_pattern(), vec3_allowed,
              "Velocity of the rigid blocks at the start (m/s; components not held).");
  prm.declare("Initial spin", "0, 0, 0", vec3_pattern(), vec3_allowed,
              "Angular velocity of the rigid blocks about their centroids at the start (rad/s).");
  declare_time_function(prm, "'Force' and the prescribed 'Velocity'");
  prm.leave();
}

/// A 'Load N' into `into`; `path` is its subsection as messages name it
/// ("Stage 2 / Load 1" in a stage, whose load starts with the stage and so
/// takes no rate and no initial motion).
void parse_load(ParameterFile& prm, const std::string& section, const std::string& path,
                const Scene& scene, BoundarySet& into)
{
  prm.enter(section);
  BlockLoad load;
  const std::string group = prm.get("Group");
  check_group_name(prm, "Group", scene, group);
  load.force = prm.get_vec3("Force");
  load.force_rate = prm.get_vec3("Force rate");
  load.prescribe_velocity = prm.get_bool("Prescribe velocity");
  load.velocity = prm.get_vec3("Velocity");
  const std::string held = prm.get("Held components");
  for (int d = 0; d < 3; ++d)
    load.held[d] = held.find("xyz"[d]) != std::string::npos;
  load.hold_rotation = prm.get_bool("Hold rotation");
  load.initial_velocity = prm.get_vec3("Initial velocity");
  load.initial_spin = prm.get_vec3("Initial spin");
  if (path != section)
    for (const char* entry : {"Force rate", "Initial velocity", "Initial spin"})
      if (prm.get_vec3(entry) != Vec3::Zero())
        throw prm.error(entry,
                        "is not taken by a stage's load (a stage's force is constant "
                        "and its blocks start from where the stages before left them)",
                        "0, 0, 0 in a stage; a force that changes: a stage with 'Time limit' for "
                        "each value");
  load.motion = parse_time_function(prm, load.prescribe_velocity,
                                    "value unless 'Prescribe velocity = true'");
  if (load.motion.acceleration && load.force != Vec3::Zero())
    throw prm.error("Force", "is not taken with 'Input = acceleration' (which drives the velocity)",
                    "0, 0, 0 with an acceleration input; a force in time: 'Input = value'");
  into.loads.push_back(load);
  into.load_groups.push_back(group);
  into.load_sections.push_back(path);
  prm.leave();
}

// ---- Deformable blocks, their boundaries and initial stress --------------------

void declare_deformable(ParameterFile& prm)
{
  prm.enter("Deformable");
  prm.declare("Groups", "", P::List(P::Anything()), "group names separated by commas",
              "Blocks of these groups are deformable (meshed into tetrahedral zones).");
  prm.declare("Edge length", "1", P::Double(), "a number > 0 (m)",
              "Target zone edge length (m); with grading, the length away from the fine region.");
  prm.declare("Fine edge length", "0", P::Double(), "a number >= 0 and < 'Edge length' (m)",
              "Zone edge length at the fine region (the excavations, or 'Fine box'), growing "
              "linearly to 'Edge length' at 'Grading distance' from it; 0: no grading.");
  prm.declare("Grading distance", "10", P::Double(), "a number > 0 (m)",
              "Distance from the fine region over which the edge length grows (m).");
  prm.declare("Fine region", "excavations", P::Selection("excavations|box|shape"),
              "excavations, box or shape",
              "Where the zones are fine: at every excavation, in the box between 'Fine box min' "
              "and 'Fine box max', or in the region of subsection 'Fine shape'.");
  declare_box(prm, "Fine box min", "Fine box max", "the fine region when 'Fine region' is box");
  prm.enter("Fine shape");
  declare_region(prm, "the fine region when 'Fine region' is shape");
  prm.leave();
  prm.declare("Mesher", "automatic", P::Selection("automatic|gmsh|lattice"),
              "automatic, gmsh or lattice",
              "Mesher of convex blocks other than axis-aligned bricks: the lattice Delaunay mesher "
              "(fast) where the edge length varies by at most 25 % over the block and gmsh's "
              "Delaunay mesher elsewhere (automatic), or one of them for every such block.");
  prm.declare("Mesh file", "", P::Anything(), "a gmsh .msh file of linear tetrahedra (or empty)",
              "The deformable body's zones from a gmsh file instead of meshing the block (relative "
              "paths start at this parameter file's folder).");
  prm.declare(
      "Nodal mixed discretization", "false", P::Bool(), "true or false",
      "Average the zones' volumetric strain and plastic pressure at the gridpoints (eqs. "
      "68-76): constant-strain tetrahedra then do not lock in incompressible or plastic flow.");
  prm.declare("Nodal mixed groups", "", P::List(P::Anything()),
              "group names separated by commas (some of 'Groups')",
              "Deformable blocks of these groups have nodal mixed discretization, the others "
              "not ('Nodal mixed discretization = true' gives it to all of them).");
  prm.declare(
      "Element", "tet4", P::Selection("tet4|tet10|hex-mixed"), "tet4, tet10 or hex-mixed",
      "Zone type: 4-node constant-strain tetrahedra, 10-node tetrahedra, or hexahedral zones of "
      "two overlays of five tetrahedra (mixed discretization, eqs. 60-67; brick blocks only).");
  prm.declare("Implicit check", "false", P::Bool(), "true or false",
              "After a static run of elastic zones, solve the same problem implicitly (CG with "
              "algebraic multigrid) and print the difference.");
  declare_zone_constants(prm);
  prm.leave();
  prm.enter("Initial stress");
  prm.declare("Stress", "0, 0, 0, 0, 0, 0", P::List(P::Double(), 6, 6, ","),
              "six numbers: xx, yy, zz, xy, yz, zx (Pa, tension positive)",
              "Zone stress at the reference height (Pa).");
  prm.declare("Gradient", "0, 0, 0, 0, 0, 0", P::List(P::Double(), 6, 6, ","), "six numbers (Pa/m)",
              "Change of each component per metre of height (Pa/m).");
  prm.declare("Reference z", "0", P::Double(), "a number (m)", "Height where 'Stress' holds (m).");
  prm.leave();
}

void parse_deformable(ParameterFile& prm, Scene& scene)
{
  prm.enter("Deformable");
  DeformableSpec& d = scene.deformable;
  for (const std::string& g : dealii::Utilities::split_string_list(prm.get("Groups")))
  {
    check_group_name(prm, "Groups", scene, g);
    d.groups.push_back(g);
  }
  d.edge_length = EdgeLengthField(prm.get_double("Edge length"));
  d.implicit_check = prm.get_bool("Implicit check");
  const std::string mesher = prm.get("Mesher");
  d.mesher = mesher == "gmsh"      ? ConvexMesher::gmsh
             : mesher == "lattice" ? ConvexMesher::lattice
                                   : ConvexMesher::automatic;
  d.material.nodal_mixed = prm.get_bool("Nodal mixed discretization");
  const std::string element = prm.get("Element");
  d.material.element = element == "hex-mixed" ? ZoneElement::hex_mixed
                       : element == "tet10"   ? ZoneElement::tet10
                                              : ZoneElement::tet4;
  if (d.material.element == ZoneElement::hex_mixed && !prm.get("Mesh file").empty())
    throw prm.error("Element",
                    "hex-mixed meshes brick blocks into hexahedra itself and cannot use the "
                    "tetrahedra of 'Mesh file'",
                    "tet4 or tet10 with a mesh file, or hex-mixed without one");
  if (d.material.element == ZoneElement::hex_mixed && d.material.nodal_mixed)
    throw prm.error("Element",
                    "hex-mixed averages over its hexahedra and does not combine with 'Nodal mixed "
                    "discretization = true'",
                    "tet4 with nodal mixed discretization, or hex-mixed without it");
  for (const std::string& g : dealii::Utilities::split_string_list(prm.get("Nodal mixed groups")))
  {
    if (std::find(d.groups.begin(), d.groups.end(), g) == d.groups.end())
      throw prm.error("Nodal mixed groups", "names '" + g + "', which is not in 'Groups'",
                      "names of deformable groups");
    if (d.material.element != ZoneElement::tet4)
      throw prm.error("Nodal mixed groups",
                      "names '" + g + "', but 'Element' is " + element +
                          (d.material.element == ZoneElement::tet10
                               ? " (10-node zones do not lock and need no mixed discretization)"
                               : " (hex-mixed averages over its hexahedra already)"),
                      "no groups with Element " + element + ", or Element tet4");
    d.nodal_mixed_groups.push_back(g);
  }
  if (d.material.element == ZoneElement::tet10 && d.material.nodal_mixed)
    throw prm.error("Element",
                    "tet10 cannot be combined with 'Nodal mixed discretization = true' (10-node "
                    "zones do not lock and need no mixed discretization)",
                    "tet4 with nodal mixed discretization, or tet10 without it");
  d.mesh_file = prm.get("Mesh file");
  if (!d.mesh_file.empty())
  {
    std::filesystem::path path(d.mesh_file);
    if (path.is_relative())
      path = std::filesystem::path(prm.file_of("Mesh file")).parent_path() / path;
    if (!std::filesystem::is_regular_file(path))
      throw prm.error("Mesh file", "names '" + path.string() + "', which is not a readable file",
                      "a gmsh .msh file of linear tetrahedra");
    d.mesh_file = path.string();
    // Read it now, so that a bad mesh stops the run before anything is
    // written.
    try
    {
      // In slabs; a body with nodal mixed discretization is put in columns
      // when its group is known (solve_deformable).
      d.mesh = std::make_shared<TetMesh>(read_gmsh_block(d.mesh_file, 0));
      measure_mesh(*d.mesh);
    }
    catch (const InputError& e)
    {
      throw prm.error("Mesh file", e.what(), "a gmsh .msh file (2.2 or 4.1) of linear tetrahedra");
    }
  }
  if (!(d.edge_length.coarse > 0.0))
    throw prm.error("Edge length", "must be positive", "a number > 0 (m)");
  const double fine = prm.get_double("Fine edge length");
  if (!(fine >= 0.0 && fine < d.edge_length.coarse))
    throw prm.error(
        "Fine edge length",
        number(fine) + " m is not below 'Edge length' (" + number(d.edge_length.coarse) + " m)",
        "0 (no grading), or a number > 0 and < " + number(d.edge_length.coarse) + " (m)");
  if (fine > 0.0)
  {
    d.edge_length.fine = fine;
    d.edge_length.distance = prm.get_double("Grading distance");
    if (!(d.edge_length.distance > 0.0))
      throw prm.error("Grading distance", "must be positive", "a number > 0 (m)");
    if (prm.get("Fine region") == "box")
      d.edge_length.near.push_back(
          ConvexRegion::box(read_box(prm, "Fine box min", "Fine box max")));
    else if (prm.get("Fine region") == "shape")
    {
      prm.enter("Fine shape");
      std::string description;
      d.edge_length.near.push_back(parse_region(prm, scene.brick, description));
      prm.leave();
    }
    else
    {
      for (const ExcavationSpec& e : scene.excavations)
        d.edge_length.near.push_back(e.region);
      for (const StageSpec& stage : scene.stages) // where stages will excavate
        for (const ExcavationSpec& e : stage.excavations)
          d.edge_length.near.push_back(e.region);
      if (d.edge_length.near.empty())
        throw prm.error("Fine edge length",
                        "asks for fine zones at the excavations, and the scene has none",
                        "0, or 'Fine region = box' with 'Fine box min' and 'Fine box max', or "
                        "'Fine region = shape' with subsection 'Fine shape'");
    }
  }
  parse_zone_constants(prm, "Deformable", d.material, false);
  d.material.density = scene.density;
  prm.leave();

  prm.enter("Initial stress");
  const auto six = [&](const std::string& name, double* out)
  {
    const std::vector<double> values = prm.get_doubles(name);
    for (int c = 0; c < 6; ++c)
      out[c] = values.at(c);
  };
  six("Stress", scene.initial_stress.base);
  six("Gradient", scene.initial_stress.gradient);
  scene.initial_stress.z0 = prm.get_double("Reference z");
  for (int c = 0; c < 6; ++c)
    scene.has_initial_stress |=
        scene.initial_stress.base[c] != 0.0 || scene.initial_stress.gradient[c] != 0.0;
  prm.leave();
}

void declare_boundary(ParameterFile& prm, const std::string& section)
{
  prm.enter(section);
  declare_region(prm, "the boundary: the gridpoints of deformable blocks in it (fixed, "
                      "velocity, load), or the faces in it (pressure, traction: zone faces by "
                      "their centroid; of rigid blocks, the parts in a box, or the faces wholly "
                      "in another shape)");
  prm.declare(
      "Condition", "fixed", P::Selection("fixed|velocity|pressure|traction|load|quiet"),
      "fixed, velocity, pressure, traction, load or quiet",
      "fixed: held in place; velocity: held at 'Velocity'; pressure: 'Pressure' on the boundary "
      "faces; traction: 'Traction' on the boundary faces; load: 'Force' on every gridpoint; "
      "quiet: viscous dashpots on the zones' boundary faces (dynamic stages), with an "
      "optional 'Stress wave' put in through them.");
  prm.declare("Stress wave", "none", P::Selection("none|harmonic|half-sine"),
              "none, harmonic or half-sine",
              "quiet: the normal stress of a wave entering through the faces: harmonic, 'Wave "
              "amplitude' sin(2 pi 'Wave frequency' (t - 'Wave start')) until 'Wave end'; "
              "half-sine, a pulse 'Wave amplitude' sin(pi (t - 'Wave start') / 'Wave "
              "duration'). Twice it is applied as a pressure on the faces.");
  prm.declare("Wave amplitude", "0", P::Double(), "a number (Pa; positive pushes in)",
              "quiet: the incident wave's normal stress amplitude (Pa).");
  prm.declare("Wave frequency", "0", P::Double(0.0), "a number > 0 (Hz)",
              "quiet, harmonic wave: its frequency (Hz).");
  prm.declare("Wave start", "0", P::Double(0.0), "a number >= 0 (s)",
              "quiet: the model time the wave starts (s).");
  prm.declare("Wave end", "0", P::Double(0.0), "a number >= 0 (s; 0: no end)",
              "quiet, harmonic wave: the model time it stops (s).");
  prm.declare("Wave duration", "0", P::Double(0.0), "a number > 0 (s)",
              "quiet, half-sine wave: the pulse's length (s).");
  prm.declare("Wave direction", "0, 0, 0", vec3_pattern(), vec3_allowed + " (0, 0, 0: inward)",
              "quiet: the direction of the incident wave's stress on the faces; along them, a "
              "shear wave (0, 0, 0: their inward normal, a pressure wave).");
  prm.declare("Traction", "0, 0, 0", vec3_pattern(), vec3_allowed,
              "Force per unit area on the boundary faces whose centroid lies in the region (Pa).");
  prm.declare("Force", "0, 0, 0", vec3_pattern(), vec3_allowed,
              "Force on each gridpoint in the region (N).");
  prm.declare("Held components", "x, y, z", P::MultipleSelection("x|y|z"),
              "some of x, y, z separated by commas", "Components held (fixed or velocity).");
  prm.declare("Velocity", "0, 0, 0", vec3_pattern(), vec3_allowed, "Held velocity (m/s).");
  prm.declare("Velocity until", "0", P::Double(0.0), "a number >= 0 (s; 0: for the whole run)",
              "velocity: the gridpoints move at 'Velocity' until this model time, then stay "
              "held where they are (s).");
  prm.declare("Report reaction", "false", P::Bool(), "true or false",
              "fixed or velocity: the force the held gridpoints take on this boundary's 'Held "
              "components' goes to the history and the summary (N).");
  prm.declare("Pressure", "0", P::Double(), "a number (Pa; positive pushes into the block)",
              "Normal pressure on the boundary faces whose centroid lies in the region (Pa).");
  declare_time_function(prm, "'Velocity', 'Pressure', 'Traction' or 'Force'");
  prm.leave();
}

/// A 'Boundary N' into `into` (reactions to report into the scene); `path`
/// as for parse_load.
void parse_boundary(ParameterFile& prm, const std::string& section, const std::string& path,
                    Scene& scene, BoundarySet& into)
{
  prm.enter(section);
  std::string description;
  const ConvexRegion region = parse_region(prm, scene.brick, description);
  const std::string condition = prm.get("Condition");
  if (path != section)
  {
    if (prm.get_double("Velocity until") > 0.0)
      throw prm.error("Velocity until",
                      "is not taken in a stage (it counts model time from the "
                      "run's start)",
                      "0 in a stage; a velocity for a while: a stage with 'Time limit', then a "
                      "stage whose 'Boundary N' of the same number holds the gridpoints fixed");
    if (prm.get_bool("Report reaction"))
      throw prm.error("Report reaction",
                      "is not taken in a stage (the history's columns are "
                      "set when the run starts)",
                      "false in a stage; report it on a 'Boundary N' of the file's top level "
                      "with the same box");
  }
  const TimeFunction motion = parse_time_function(prm, condition == "velocity",
                                                  "value unless 'Condition = velocity'");
  if (motion.varies() && (condition == "fixed" || condition == "quiet"))
    throw prm.error("Time function",
                    "varies nothing on a " + condition + " boundary" +
                        (condition == "quiet" ? " (its 'Stress wave' puts a wave in)" : ""),
                    "none with 'Condition = fixed' or quiet; a time function with velocity, "
                    "pressure, traction or load");
  (condition == "pressure" || condition == "traction" || condition == "quiet"
       ? into.face_pressure_sections
       : into.gridpoint_condition_sections)
      .push_back(path);
  const std::string wave = prm.get("Stress wave");
  if (wave != "none" && condition != "quiet")
    throw prm.error("Stress wave", "needs a quiet boundary (the wave enters through its dashpots)",
                    "none, or 'Condition' quiet");
  if (condition == "quiet")
  {
    FacePressure q;
    q.region = region;
    q.quiet = true;
    q.wave.amplitude = prm.get_double("Wave amplitude");
    q.wave.start = prm.get_double("Wave start");
    q.wave_direction = prm.get_vec3("Wave direction");
    if (q.wave_direction != Vec3::Zero())
      q.wave_direction.normalize();
    if (wave == "harmonic")
    {
      q.wave.kind = WaveSignal::Kind::harmonic;
      q.wave.frequency = prm.get_double("Wave frequency");
      q.wave.end = prm.get_double("Wave end");
      if (!(q.wave.frequency > 0.0))
        throw prm.error("Wave frequency", "must be positive for a harmonic 'Stress wave'",
                        "a frequency > 0 (Hz)");
      if (q.wave.end != 0.0 && q.wave.end <= q.wave.start)
        throw prm.error("Wave end", "is not after 'Wave start'",
                        "0 (no end) or a time after 'Wave start' (s)");
    }
    else if (wave == "half-sine")
    {
      q.wave.kind = WaveSignal::Kind::half_sine;
      q.wave.duration = prm.get_double("Wave duration");
      if (!(q.wave.duration > 0.0))
        throw prm.error("Wave duration", "must be positive for a half-sine 'Stress wave'",
                        "the pulse's length > 0 (s)");
    }
    into.face_pressures.push_back(q);
  }
  else if (condition == "pressure")
  {
    FacePressure p;
    p.region = region;
    p.pressure = prm.get_double("Pressure");
    p.motion = motion;
    into.face_pressures.push_back(p);
  }
  else if (condition == "traction")
  {
    FacePressure p;
    p.region = region;
    p.traction = prm.get_vec3("Traction");
    p.motion = motion;
    into.face_pressures.push_back(p);
  }
  else if (condition == "load")
  {
    GridpointCondition c;
    c.region = region;
    c.held[0] = c.held[1] = c.held[2] = false;
    c.force = prm.get_vec3("Force");
    c.motion = motion;
    into.gridpoint_conditions.push_back(c);
  }
  else
  {
    GridpointCondition c;
    c.region = region;
    const std::string held = prm.get("Held components");
    for (int d = 0; d < 3; ++d)
      c.held[d] = held.find("xyz"[d]) != std::string::npos;
    if (condition == "velocity")
    {
      c.velocity = prm.get_vec3("Velocity");
      if (prm.get_double("Velocity until") > 0.0)
        c.velocity_until = prm.get_double("Velocity until");
      c.motion = motion;
    }
    into.gridpoint_conditions.push_back(c);
    if (prm.get_bool("Report reaction"))
      scene.reactions.push_back(ReactionReport{section, region, {c.held[0], c.held[1], c.held[2]}});
  }
  if (prm.get_bool("Report reaction") && condition != "fixed" && condition != "velocity")
    throw prm.error("Report reaction", "needs held gridpoints",
                    "true only with 'Condition' fixed or velocity");
  prm.leave();
}

// ---- Output ------------------------------------------------------------------

void declare_output(ParameterFile& prm)
{
  prm.enter("Output");
  prm.declare("Directory", "output", P::Anything(), "a writable folder (created if missing)",
              "Folder for every file the run writes.");
  prm.declare("Base name", "talus", P::Anything(), "a file name prefix",
              "Prefix of the files written.");
  prm.declare("Write VTU", "true", P::Bool(), "true or false", "Write ParaView files.");
  prm.declare("VTU encoding", "binary", P::Selection("binary|ascii"), "binary or ascii",
              "Data arrays of the VTU files: zlib-compressed binary, or ASCII text to read.");
  prm.declare("Checkpoint interval", "0", P::Integer(0), "an integer >= 0 (0: only on a signal)",
              "Steps between checkpoints (<Base name>_checkpoint.bin, for talus --restart); "
              "SIGINT and SIGTERM always write one.");
  prm.leave();
}

void parse_output(ParameterFile& prm, Scene& scene)
{
  prm.enter("Output");
  scene.output.directory = prm.get("Directory");
  // A run of a shipped scene somewhere else (the tests of tests/parallel
  // run them where their own output file is named "output").
  if (const char* elsewhere = std::getenv("TALUS_OUTPUT_DIRECTORY"); elsewhere && *elsewhere)
    scene.output.directory = elsewhere;
  scene.output.base_name = prm.get("Base name");
  const std::string& base = scene.output.base_name;
  if (base.empty() || base.size() > 200 || base.find('/') != std::string::npos ||
      std::any_of(base.begin(), base.end(),
                  [](char c) { return static_cast<unsigned char>(c) < 32 || c == 127; }))
    throw prm.error("Base name", "must be a plain file name",
                    "a name of 1 to 200 characters without '/' or control characters");
  scene.output.write_vtu = prm.get_bool("Write VTU");
  scene.output.vtu_encoding =
      prm.get("VTU encoding") == "ascii" ? VtuEncoding::ascii : VtuEncoding::binary;
  scene.output.checkpoint_interval =
      static_cast<unsigned long>(prm.get_integer("Checkpoint interval"));
  prm.leave();
}

// ---- Solver, contacts and joints ------------------------------------------

/// TALUS_MAX_STEPS, when set, caps every scene's 'Steps' (tests that run
/// many scenes keep each one short with it).
unsigned long step_limit_from_environment()
{
  const char* text = std::getenv("TALUS_MAX_STEPS");
  if (text == nullptr)
    return std::numeric_limits<unsigned long>::max();
  char* end = nullptr;
  errno = 0;
  const unsigned long limit = std::strtoul(text, &end, 10);
  if (end == text || *end != '\0' || errno != 0 || text[0] == '-')
    throw InputError(std::string("environment variable TALUS_MAX_STEPS: '") + text +
                     "' is not a number of steps; allowed: an integer >= 0, or unset");
  return limit;
}

void declare_solver(ParameterFile& prm)
{
  prm.enter("Solver");
  prm.declare("Mode", "static", P::Selection("static|dynamic|factor of safety"),
              "static, dynamic or factor of safety",
              "static: damped to equilibrium; dynamic: motion in time (damped only by 'Rayleigh "
              "...' and 'Dynamic local damping'); factor of safety: static trials with the "
              "strengths divided by F, bisected on F.");
  prm.declare("Steps", "0", P::Integer(0), "an integer >= 0",
              "Step limit; 0 builds and writes the model only.");
  prm.declare("End time", "0", P::Double(0.0), "a number >= 0 (s; 0: none)",
              "The run stops at this model time, or at 'Steps', whichever comes first (s).");
  prm.declare("Target ratio", "1e-5", P::Double(0.0), "a number >= 0",
              "A static run stops when the unbalanced-force ratio falls below this (0: never).");
  prm.declare("Damping", "local", P::Selection("local|combined|global"),
              "local, combined or global",
              "Damping of static runs: local (eqs. 78-79), combined (eq. 83, for steady motion) or "
              "adaptive global (eq. 77).");
  prm.declare("Local damping", "0.8", P::Double(0.0, 1.0), "a number from 0 to 1",
              "alpha of local and combined damping (eqs. 79, 83).");
  prm.declare("Global damping ratio", "0.5", P::Double(0.0, 1.0), "a number from 0 to 1",
              "R of eq. 77: damping power over the rate of change of kinetic energy.");
  prm.declare("Density scaling", "true", P::Bool(), "true or false",
              "Static runs: raise inertial masses to the mean block mass (faster convergence).");
  prm.declare("Partial density scaling", "false", P::Bool(), "true or false",
              "Dynamic runs with a 'Time step': gridpoints and rigid blocks whose own stable step "
              "(eqs. 84, 87) is smaller get inertial mass to reach it (eq. 89); others keep "
              "their true mass.");
  prm.declare("Added mass limit", "0.01", P::Double(0.0, 1.0), "a number from 0 to 1",
              "Partial density scaling: the largest mass it may add, as a fraction of the total "
              "mass of the free blocks and zones.");
  prm.declare("Added mass over limit", "refuse", P::Selection("refuse|warn"), "refuse or warn",
              "Partial density scaling above 'Added mass limit': refuse the run, or warn and go "
              "on.");
  prm.declare("Rayleigh damping ratio", "0", P::Double(0.0, 1.0), "a number from 0 to 1",
              "Dynamic runs: xi_min, the least fraction of critical damping of Rayleigh damping, "
              "reached at 'Rayleigh frequency' (0: none).");
  prm.declare("Rayleigh frequency", "0", P::Double(0.0), "a number > 0 (Hz)",
              "Dynamic runs: f_min (Hz), the centre frequency of Rayleigh damping.");
  prm.declare("Rayleigh alpha", "0", P::Double(0.0), "a number >= 0 (1/s)",
              "Dynamic runs: the mass-proportional coefficient of Rayleigh damping (1/s), instead "
              "of a ratio and a frequency.");
  prm.declare("Rayleigh beta", "0", P::Double(0.0), "a number >= 0 (s)",
              "Dynamic runs: the stiffness-proportional coefficient of Rayleigh damping (s).");
  prm.declare("Dynamic local damping", "0", P::Double(0.0, 1.0), "a number from 0 to 1",
              "Dynamic runs: alpha of local damping (eqs. 78-79); 0: none.");
  prm.declare("Rotation", "isotropic", P::Selection("isotropic|principal"),
              "isotropic or principal",
              "isotropic: the manual's approximate inertia (eq. 46); principal: full inertia "
              "with Euler's equations (eqs. 45, 49), for dynamics.");
  prm.declare("Time step fraction", "0.1", P::Double(0.0, 1.0), "a number in (0, 1]",
              "frac of eq. 87.");
  prm.declare("Time step", "0", P::Double(0.0), "a number >= 0 (s; 0: automatic)",
              "Fixed time step (s); 0 uses eq. 87.");
  prm.declare("Gravity", "0, 0, -9.81", vec3_pattern(), vec3_allowed, "Gravity (m/s^2).");
  prm.declare("Fixed groups", "", P::List(P::Anything()), "group names separated by commas",
              "Blocks of these groups do not move.");
  prm.declare(
      "History points", "", P::Anything(), "points 'x, y, z' separated by ';' (m)",
      "Deformable blocks: the displacement and velocity of the gridpoint nearest each point and "
      "the stress of the zone nearest it go to the history.");
  prm.declare("History blocks", "", P::List(P::Integer(0, 2000000000)),
              "block numbers separated by commas",
              "Blocks whose displacement and velocity are written to the history.");
  prm.declare("History block points", "", P::Anything(), "points 'x, y, z' separated by ';' (m)",
              "The blocks containing (or, outside every block, nearest to) these points are "
              "recorded as 'History blocks' are.");
  prm.declare("History interval", "10", P::Integer(1, 1000000000), "an integer from 1 to 1e9",
              "Steps between history rows.");
  prm.declare("Output interval", "0", P::Integer(0), "an integer >= 0 (0: first and last)",
              "Steps between VTU files.");
  prm.declare("Factor tolerance", "0.005", P::Double(1e-6, 1.0), "a number from 1e-6 to 1",
              "Factor of safety: the search stops when the bracket is narrower than this "
              "fraction of its stable end.");
  prm.declare("Initial factor", "1", P::Double(0.01, 100.0), "a number from 0.01 to 100",
              "Factor of safety: F of the first trial.");
  prm.declare("Reduce zone strength", "false", P::Bool(), "true or false",
              "Factor of safety: divide the Mohr-Coulomb zones' strengths by F too.");
  prm.leave();

  prm.enter("Contacts");
  prm.declare("Tolerance", "0", P::Double(0.0),
              "a number >= 0 (m; 0: 0.5 % of the mean block size)",
              "CTOL: contacts are made within this gap and deleted beyond it (m).");
  prm.declare("Update period", "10", P::Integer(1, 1000000000), "an integer from 1 to 1e9",
              "Steps between common-plane and sub-contact updates.");
  prm.declare("Rotation constant", "0", P::Double(), "a number (m)", "K_T of eq. 12 (m).");
  prm.declare(
      "Point area fraction", "0.01", P::Double(0.0), "a number > 0",
      "Area of a vertex or edge sub-contact, as a fraction of volume^(2/3) of the smaller block.");
  prm.declare(
      "Update motion fraction", "0.01", P::Double(0.0), "a number >= 0 (0: update every contact)",
      "At an update, a contact whose two blocks moved less than this fraction of the tolerance "
      "since its last update keeps its plane and sub-contacts.");
  prm.leave();

  prm.enter("Joint properties");
  declare_joint_properties(prm);
  prm.leave();
}

/// The points of `entry` (x, y, z separated by ';', m), each finite.
std::vector<Vec3> get_points(ParameterFile& prm, const std::string& entry)
{
  std::vector<Vec3> points;
  for (const std::string& point : dealii::Utilities::split_string_list(prm.get(entry), ';'))
  {
    const auto xyz = dealii::Utilities::split_string_list(point, ',');
    Vec3 p;
    bool good = xyz.size() == 3;
    for (unsigned int d = 0; good && d < 3; ++d)
    {
      char* end = nullptr;
      p[d] = std::strtod(xyz[d].c_str(), &end);
      good = end != xyz[d].c_str() && *end == '\0' && std::isfinite(p[d]);
    }
    if (!good)
      throw prm.error(entry, "'" + point + "' is not a point of finite coordinates",
                      "points 'x, y, z' separated by ';' (m)");
    points.push_back(p);
  }
  return points;
}

void parse_joint_properties_section(ParameterFile& prm, Scene& scene)
{
  prm.enter("Joint properties");
  scene.solver.joint = parse_joint_properties(prm, "Joint properties", nullptr);
  prm.leave();
}

void parse_solver(ParameterFile& prm, Scene& scene)
{
  SolverSettings& s = scene.solver;
  prm.enter("Solver");
  s.dynamic = prm.get("Mode") == "dynamic";
  s.steps = static_cast<unsigned long>(prm.get_integer("Steps"));
  s.steps = std::min(s.steps, step_limit_from_environment());
  s.end_time = prm.get_double("End time");
  s.target_ratio = prm.get_double("Target ratio");
  s.local_damping = prm.get_double("Local damping"); // used only when static
  const std::string damping = prm.get("Damping");
  s.damping = damping == "local"      ? Damping::local
              : damping == "combined" ? Damping::combined
                                      : Damping::adaptive_global;
  s.global_damping_ratio = prm.get_double("Global damping ratio");
  if (!(s.global_damping_ratio > 0.0) && s.damping == Damping::adaptive_global)
    throw prm.error("Global damping ratio", "must be positive for global damping",
                    "a number > 0 and <= 1");
  s.density_scaling = prm.get_bool("Density scaling");
  // Rayleigh damping of dynamics, xi(omega) = (alpha / omega + beta omega)
  // / 2: as the least ratio xi_min at omega_min = 2 pi f_min (alpha =
  // xi_min omega_min, beta = xi_min / omega_min), or as the coefficients.
  {
    const std::map<std::string, unsigned int> set_here = prm.lines();
    const auto given = [&](const std::string& entry)
    { return set_here.count("Solver / " + entry) > 0; };
    const bool as_ratio = given("Rayleigh damping ratio") || given("Rayleigh frequency");
    const bool as_coefficients = given("Rayleigh alpha") || given("Rayleigh beta");
    if (as_ratio && as_coefficients)
      throw prm.error(given("Rayleigh alpha") ? "Rayleigh alpha" : "Rayleigh beta",
                      "gives Rayleigh damping a second time: the file also sets '" +
                          std::string(given("Rayleigh damping ratio") ? "Rayleigh damping ratio"
                                                                      : "Rayleigh frequency") +
                          "'",
                      "either 'Rayleigh damping ratio' with 'Rayleigh frequency', or 'Rayleigh "
                      "alpha' and 'Rayleigh beta', not both");
    if (as_ratio)
    {
      const double xi = prm.get_double("Rayleigh damping ratio");
      const double omega = 2.0 * M_PI * prm.get_double("Rayleigh frequency");
      if (xi > 0.0 && !(omega > 0.0))
        throw prm.error("Rayleigh frequency", "must be positive with a 'Rayleigh damping ratio'",
                        "a number > 0 (Hz)");
      s.rayleigh_alpha = xi * omega;
      s.rayleigh_beta = xi > 0.0 ? xi / omega : 0.0;
    }
    else
    {
      s.rayleigh_alpha = prm.get_double("Rayleigh alpha");
      s.rayleigh_beta = prm.get_double("Rayleigh beta");
    }
    s.dynamic_local_damping = prm.get_double("Dynamic local damping");
  }
  s.principal_inertia = prm.get("Rotation") == "principal";
  s.time_step_fraction = prm.get_double("Time step fraction");
  if (!(s.time_step_fraction > 0.0))
    throw prm.error("Time step fraction", "must be positive", "a number in (0, 1]");
  s.time_step = prm.get_double("Time step");
  s.partial_density_scaling = prm.get_bool("Partial density scaling");
  s.added_mass_limit = prm.get_double("Added mass limit");
  s.added_mass_warn = prm.get("Added mass over limit") == "warn";
  if (s.partial_density_scaling && !(s.time_step > 0.0))
    throw prm.error("Partial density scaling", "needs the step it scales to: 'Time step' is 0",
                    "false, or true with a 'Time step' > 0 (s)");
  s.source = scene.parameter_file;
  s.gravity = prm.get_vec3("Gravity");
  for (const std::string& g : dealii::Utilities::split_string_list(prm.get("Fixed groups")))
  {
    check_group_name(prm, "Fixed groups", scene, g);
    scene.fixed_groups.push_back(g);
  }
  s.history_points = get_points(prm, "History points");
  scene.history_block_points = get_points(prm, "History block points");
  for (const std::string& b : dealii::Utilities::split_string_list(prm.get("History blocks")))
    s.history_blocks.push_back(static_cast<unsigned int>(std::stoul(b)));
  s.history_interval = static_cast<unsigned int>(prm.get_integer("History interval"));
  s.output_interval = static_cast<unsigned long>(prm.get_integer("Output interval"));
  StrengthReductionSettings& f = scene.strength_reduction;
  f.enabled = prm.get("Mode") == "factor of safety";
  f.tolerance = prm.get_double("Factor tolerance");
  f.initial_factor = prm.get_double("Initial factor");
  f.reduce_zone_strength = prm.get_bool("Reduce zone strength");
  if (f.enabled && !(s.target_ratio > 0.0))
    throw prm.error("Target ratio",
                    "must be positive with 'Mode' = factor of safety (a trial is stable when "
                    "its unbalanced-force ratio falls below it)",
                    "a number > 0, e.g. 1e-5");
  if (f.enabled && s.steps == 0)
    throw prm.error("Steps",
                    "must be positive with 'Mode' = factor of safety (the step limit of each "
                    "trial)",
                    "an integer > 0");
  prm.leave();

  prm.enter("Contacts");
  s.contact.tolerance = prm.get_double("Tolerance");
  if (s.contact.tolerance == 0.0)
    s.contact.tolerance = 0.005 * std::cbrt(scene.brick.volume()); // refined once blocks exist
  s.contact.update_period = static_cast<unsigned int>(prm.get_integer("Update period"));
  s.contact.rotation_constant = prm.get_double("Rotation constant");
  s.contact.point_area_fraction = prm.get_double("Point area fraction");
  s.contact.update_motion_fraction = prm.get_double("Update motion fraction");
  if (!(s.contact.point_area_fraction > 0.0))
    throw prm.error("Point area fraction", "must be positive", "a number > 0");
  prm.leave();

}

/// Warnings about entries that the file sets and the run ignores (legal,
/// but surely not meant); check_built_model prints them.
void warn_ignored(const ParameterFile& prm, const std::string& section,
                  const std::vector<std::string>& entries, const std::string& why,
                  std::vector<std::string>& warnings)
{
  const std::map<std::string, unsigned int> lines = prm.lines();
  const std::map<std::string, std::string> files = prm.line_files();
  for (const std::string& entry : entries)
  {
    const std::string key = section + " / " + entry;
    if (lines.count(key) == 0)
      continue;
    const std::string file = files.count(key) ? files.at(key) : prm.filename();
    // The file's name as the summary shows it ("talus: scene NAME").
    const std::string name = std::filesystem::path(file).filename().string();
    warnings.push_back(
        InputError::at(name, lines.at(key), section, entry, "is ignored: " + why, "").what());
  }
}

/// The subsections 'kind M' inside `stage`, in the order of M.
std::vector<std::string> stage_subsections(const ParameterFile& prm, const std::string& stage,
                                           const std::string& kind)
{
  std::vector<std::pair<long, std::string>> found;
  const std::regex numbered(kind + " ([0-9]{1,9})");
  for (const std::string& s : prm.sections_in(stage))
  {
    std::smatch m;
    if (std::regex_match(s, m, numbered))
      found.emplace_back(std::stol(m[1]), s);
  }
  std::sort(found.begin(), found.end());
  std::vector<std::string> names;
  for (const auto& f : found)
    names.push_back(f.second);
  return names;
}

/// The 'Excavation M' nested in stage `stage`, in the order of M.
std::vector<std::string> stage_excavations(const ParameterFile& prm, const std::string& stage)
{
  return stage_subsections(prm, stage, "Excavation");
}

/// The subsection name of a path ("Boundary 2" of "Stage 3 / Boundary 2").
std::string last_part(const std::string& path)
{
  const std::size_t k = path.rfind(" / ");
  return k == std::string::npos ? path : path.substr(k + 3);
}

/// Drops the boundaries and loads named `name` from `set`; whether any was.
bool drop_boundary(BoundarySet& set, const std::string& name)
{
  bool found = false;
  const auto drop =
      [&](auto& values, std::vector<std::string>& sections, std::vector<std::string>* groups)
  {
    for (std::size_t i = sections.size(); i-- > 0;)
      if (last_part(sections[i]) == name)
      {
        values.erase(values.begin() + i);
        sections.erase(sections.begin() + i);
        if (groups)
          groups->erase(groups->begin() + i);
        found = true;
      }
  };
  drop(set.gridpoint_conditions, set.gridpoint_condition_sections, nullptr);
  drop(set.face_pressures, set.face_pressure_sections, nullptr);
  drop(set.loads, set.load_sections, &set.load_groups);
  return found;
}

/// A stage's changes of the boundaries and loads: 'Release', then its
/// 'Boundary M' and 'Load M', each replacing the one of the same name in
/// force (the stage before's, or the file's), onto stage.boundaries.
void parse_stage_boundaries(ParameterFile& prm, const std::string& section, Scene& scene,
                            const BoundarySet& before)
{
  StageSpec& stage = scene.stages.back();
  stage.boundaries = before;
  prm.enter(section);
  for (const std::string& name : dealii::Utilities::split_string_list(prm.get("Release")))
  {
    if (!std::regex_match(name, std::regex("(Boundary|Load) [0-9]{1,9}")))
      throw prm.error("Release", "'" + name + "' is not the name of a 'Boundary N' or 'Load N'",
                      "names of the 'Boundary N' and 'Load N' in force, separated by commas");
    if (!drop_boundary(stage.boundaries, name))
      throw prm.error("Release", "names '" + name + "', which is not in force at this stage",
                      "the 'Boundary N' and 'Load N' of the file and of the stages before that "
                      "are not released yet");
    stage.boundary_changes.push_back(name + " released");
  }
  for (const std::string kind : {"Boundary", "Load"})
    for (const std::string& sub : stage_subsections(prm, section, kind))
    {
      const bool replaced = drop_boundary(stage.boundaries, sub);
      const std::string path = section + " / " + sub;
      if (kind == std::string("Boundary"))
        parse_boundary(prm, sub, path, scene, stage.boundaries);
      else
        parse_load(prm, sub, path, scene, stage.boundaries);
      stage.boundary_changes.push_back(sub + (replaced ? " replaced" : " added"));
    }
  prm.leave();
  stage.changes_boundaries = !stage.boundary_changes.empty();
}

void warn_about_ignored_entries(const ParameterFile& prm, Scene& scene,
                                const std::vector<std::pair<std::string, std::string>>& sections)
{
  if (scene.solver.dynamic)
    warn_ignored(
        prm, "Solver",
        {"Target ratio", "Damping", "Local damping", "Global damping ratio", "Density scaling"},
        "'Mode' is dynamic (no static damping; every one of 'Steps')", scene.warnings);
  bool any_dynamic = scene.solver.dynamic;
  for (const StageSpec& stage : scene.stages)
    any_dynamic |= stage.dynamic;
  if (!scene.solver.partial_density_scaling)
    warn_ignored(prm, "Solver", {"Added mass limit", "Added mass over limit"},
                 "'Partial density scaling' is false", scene.warnings);
  if (!any_dynamic)
    warn_ignored(prm, "Solver",
                 {"Rayleigh damping ratio", "Rayleigh frequency", "Rayleigh alpha", "Rayleigh beta",
                  "Dynamic local damping"},
                 "no stage is dynamic (static runs take 'Damping')", scene.warnings);
  if (!any_dynamic)
  {
    // Quiet boundaries act in dynamic stages only (each section once: a
    // stage's set holds those of the file it keeps).
    std::vector<std::string> warned;
    const auto quiet_ignored = [&](const BoundarySet& set)
    {
      for (std::size_t i = 0; i < set.face_pressures.size(); ++i)
        if (set.face_pressures[i].quiet &&
            std::find(warned.begin(), warned.end(), set.face_pressure_sections[i]) == warned.end())
        {
          warned.push_back(set.face_pressure_sections[i]);
          warn_ignored(prm, set.face_pressure_sections[i], {"Condition"},
                       "a quiet boundary acts in dynamic stages only, and no stage is dynamic",
                       scene.warnings);
        }
    };
    BoundarySet file;
    file.face_pressures = scene.face_pressures;
    file.face_pressure_sections = scene.face_pressure_sections;
    quiet_ignored(file);
    for (const StageSpec& stage : scene.stages)
      quiet_ignored(stage.boundaries);
  }
  if (scene.strength_reduction.enabled)
    warn_ignored(prm, "Solver", {"Output interval"},
                 "'Mode' is factor of safety (the last unstable trial's end is written)",
                 scene.warnings);
  if (scene.strength_reduction.enabled)
    warn_ignored(prm, "Output", {"Checkpoint interval"},
                 "'Mode' is factor of safety (trials write no checkpoints)", scene.warnings);
  else if (std::none_of(scene.stages.begin(), scene.stages.end(),
                        [](const StageSpec& stage) { return stage.factor_of_safety; }))
    warn_ignored(prm, "Solver", {"Factor tolerance", "Initial factor", "Reduce zone strength"},
                 "'Mode' is not factor of safety, in 'Solver' or in a stage", scene.warnings);
  if (scene.deformable.groups.empty())
    warn_ignored(prm, "Deformable",
                 {"Edge length",
                  "Fine edge length",
                  "Grading distance",
                  "Fine region",
                  "Fine box min",
                  "Fine box max",
                  "Mesh file",
                  "Nodal mixed discretization",
                  "Nodal mixed groups",
                  "Element",
                  "Implicit check",
                  "Zone model",
                  "Young's modulus",
                  "Poisson's ratio",
                  "Friction angle",
                  "Dilation angle",
                  "Cohesion",
                  "Tensile strength"},
                 "'Groups' names no deformable block", scene.warnings);
  std::size_t load = 0;
  for (const auto& [kind, name] : sections)
    if (kind == "Load" && !scene.solver.loads[load++].prescribe_velocity)
      warn_ignored(prm, name, {"Velocity", "Held components", "Hold rotation"},
                   "'Prescribe velocity' is false", scene.warnings);
  // The entries of the other kinds of phreatic surface.
  const WaterTable::Kind surface = scene.solver.water.table.kind();
  if (surface != WaterTable::Kind::plane)
    warn_ignored(prm, "Water", {"Level", "Point", "Normal"}, "'Phreatic surface' is not plane",
                 scene.warnings);
  if (surface != WaterTable::Kind::table)
    warn_ignored(prm, "Water", {"X values", "Y values", "Heights"},
                 "'Phreatic surface' is not table", scene.warnings);
}

} // namespace

Scene read_scene(const std::string& filename, bool prepare_output)
{
  ParameterFile prm(filename);

  // Numbered subsections exist exactly as the file names them.
  const std::regex numbered(
      "(Joint set|Joint material|Joint|Excavation|Group contact|Group|Load|Boundary|Rock "
      "material|Stage) ([0-9]+)");
  std::vector<std::tuple<std::string, long, std::string>> found; // kind, number, name
  if (prm.sections_in_file().size() > max_numbered_sections + 16)
    throw InputError(filename + ": the file has " + std::to_string(prm.sections_in_file().size()) +
                     " subsections, which would take talus longer to read than to run; allowed: "
                     "at most " +
                     std::to_string(max_numbered_sections) +
                     " numbered ones ('Joint set N', 'Joint N', ...; a joint set cuts many "
                     "parallel joints with one subsection)");
  for (const std::string& s : prm.sections_in_file())
  {
    std::smatch m;
    if (std::regex_match(s, m, numbered))
    {
      if (m[2].length() > 9)
        throw InputError(filename + ":" + std::to_string(prm.lines().at(s)) + ": subsection '" + s +
                         "': the number is too large; allowed: numbers up to 999999999");
      found.emplace_back(m[1], std::stol(m[2]), s);
    }
  }
  // The reader's work grows with the square of the number of subsections
  // (about 30 s at 10,000): refuse a file of more before reading it.
  if (found.size() > max_numbered_sections)
    throw InputError(filename + ": the file has " + std::to_string(found.size()) +
                     " numbered subsections ('Joint set N', 'Joint N', ...), which would take "
                     "talus longer to read than to run; allowed: at most " +
                     std::to_string(max_numbered_sections) +
                     " (a joint set cuts many parallel joints with one subsection)");
  // Joint set 2 is cut after Joint set 1 whatever the order in the file.
  std::sort(found.begin(), found.end());
  std::vector<std::pair<std::string, std::string>> numbered_sections; // kind, name
  for (const auto& [kind, number, name] : found)
    numbered_sections.emplace_back(kind, name);

  declare_model(prm);
  declare_material(prm);
  declare_output(prm);
  declare_solver(prm);
  declare_deformable(prm);
  declare_water(prm);
  for (const auto& [kind, name] : numbered_sections)
  {
    if (kind == "Joint set")
      declare_joint_set(prm, name);
    else if (kind == "Joint")
      declare_joint(prm, name);
    else if (kind == "Excavation")
      declare_excavation(prm, name);
    else if (kind == "Load")
      declare_load(prm, name);
    else if (kind == "Boundary")
      declare_boundary(prm, name);
    else if (kind == "Joint material")
      declare_joint_material(prm, name);
    else if (kind == "Group contact")
      declare_group_contact(prm, name);
    else if (kind == "Rock material")
      declare_rock_material(prm, name);
    else if (kind == "Stage")
    {
      declare_stage(prm, name, stage_excavations(prm, name));
      prm.enter(name);
      for (const std::string& b : stage_subsections(prm, name, "Boundary"))
        declare_boundary(prm, b);
      for (const std::string& l : stage_subsections(prm, name, "Load"))
        declare_load(prm, l);
      const std::vector<std::string> inside = prm.sections_in(name);
      if (std::find(inside.begin(), inside.end(), "Water") != inside.end())
        declare_water(prm);
      prm.leave();
    }
    else
      declare_group(prm, name);
  }

  prm.parse();

  Scene scene;
  scene.parameter_file = filename;
  parse_model(prm, scene);
  parse_material(prm, scene);
  parse_output(prm, scene);
  parse_joint_properties_section(prm, scene);
  for (const auto& [kind, name] : numbered_sections)
    if (kind == "Joint material")
      parse_joint_material(prm, name, scene);
  for (const auto& [kind, name] : numbered_sections)
  {
    if (kind == "Joint set")
    {
      scene.joint_sets.push_back(parse_joint_set(prm, name, scene));
      scene.joint_set_sections.push_back(name);
    }
    else if (kind == "Joint")
    {
      scene.joint_planes.push_back(parse_joint(prm, name, scene));
      scene.joint_plane_sections.push_back(name);
    }
    else if (kind == "Excavation")
      scene.excavations.push_back(parse_excavation(prm, name, scene));
    else if (kind == "Group")
      scene.groups.push_back(parse_group(prm, name, scene));
  }
  apply_joint_sides(prm, scene);
  parse_solver(prm, scene);
  BoundarySet boundaries; // the file's
  for (const auto& [kind, name] : numbered_sections)
    if (kind == "Load")
      parse_load(prm, name, name, scene, boundaries);
    else if (kind == "Boundary")
      parse_boundary(prm, name, name, scene, boundaries);
    else if (kind == "Group contact")
      parse_group_contact(prm, name, scene);
  scene.gridpoint_conditions = boundaries.gridpoint_conditions;
  scene.face_pressures = boundaries.face_pressures;
  scene.solver.loads = boundaries.loads;
  scene.gridpoint_condition_sections = boundaries.gridpoint_condition_sections;
  scene.face_pressure_sections = boundaries.face_pressure_sections;
  scene.load_groups = boundaries.load_groups;
  scene.load_sections = boundaries.load_sections;
  for (const auto& [kind, name] : numbered_sections)
    if (kind == "Stage")
    {
      parse_stage(prm, name, stage_excavations(prm, name), scene);
      parse_stage_boundaries(
          prm, name, scene,
          scene.stages.size() > 1 ? scene.stages[scene.stages.size() - 2].boundaries : boundaries);
    }
  parse_deformable(prm, scene);
  parse_water(prm, scene);
  {
    std::size_t k = 0;
    for (const auto& [kind, name] : numbered_sections)
      if (kind == "Stage")
      {
        StageSpec& stage = scene.stages[k++];
        const std::vector<std::string> inside = prm.sections_in(name);
        if (std::find(inside.begin(), inside.end(), "Water") == inside.end())
          continue;
        prm.enter(name);
        parse_water(prm, scene, stage.water);
        prm.leave();
        stage.changes_water = true;
      }
  }
  for (const auto& [kind, name] : numbered_sections)
    if (kind == "Rock material")
      parse_rock_material(prm, name, scene);
  {
    std::size_t k = 0;
    for (const auto& [kind, name] : numbered_sections)
      if (kind == "Stage")
        parse_stage_rock_materials(prm, name, scene, scene.stages[k++]);
  }
  for (std::size_t r = 0; r < scene.rock_materials.size(); ++r)
  {
    bool used = !scene.rock_materials[r].groups.empty();
    for (const StageSpec& stage : scene.stages)
      for (const RockMaterialChange& c : stage.rock_materials)
        used |= c.material == int(r);
    if (!used)
      warn_ignored(prm, scene.rock_materials[r].section, {"Name"},
                   "no block is made of this material (its 'Groups' is empty and no stage's "
                   "'Rock materials' gives it)",
                   scene.warnings);
  }
  if (scene.strength_reduction.enabled && !scene.deformable.mesh_file.empty())
  {
    prm.enter("Deformable");
    throw prm.error("Mesh file", "is not taken with 'Mode' = factor of safety",
                    "empty (the blocks meshed by talus) with 'Mode' = factor of safety");
  }
  warn_about_ignored_entries(prm, scene, numbered_sections);
  scene.used_parameters = prm.used_parameters();
  scene.lines = prm.lines();
  scene.line_files = prm.line_files();
  check_model_size(scene);

  // Last, once every value is known to be good: nothing is created on disk
  // for a file that is refused.
  if (prepare_output)
  {
    prm.enter("Output");
    try
    {
      prepare_output_directory(scene.output.directory);
    }
    catch (const InputError& e)
    {
      throw prm.error("Directory", e.what(), "a folder that can be created and written");
    }
    prm.leave();
  }
  return scene;
}

} // namespace talus
