#include <talus/base/memory.h>
#include <talus/io/scene_checks.h>
#include <talus/solver/rigid_face_loads.h>
#include <talus/zone/block_mesher.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>

namespace talus
{

InputError scene_error(const Scene& scene, const std::string& section, const std::string& entry,
                       const std::string& problem, const std::string& allowed)
{
  const auto line_of = [&](const std::string& key)
  {
    const auto it = scene.lines.find(key);
    return it == scene.lines.end() ? 0u : it->second;
  };
  const auto file_of = [&](const std::string& key)
  {
    const auto it = scene.line_files.find(key);
    return it == scene.line_files.end() ? scene.parameter_file : it->second;
  };
  if (!entry.empty())
  {
    const unsigned int line = line_of(section + " / " + entry);
    return InputError::at(file_of(section + " / " + entry), line, section, entry,
                          line == 0 ? problem + " (default value)" : problem, allowed);
  }
  const unsigned int line = line_of(section);
  return InputError(file_of(section) + (line > 0 ? ":" + std::to_string(line) : "") +
                    ": subsection '" + section + "': " + problem +
                    (allowed.empty() ? "" : "; allowed: " + allowed));
}

namespace
{

/// Joints of a set that cross `box` (counted along the set's normal), as a
/// double so that a tiny spacing or a huge brick cannot overflow.
double joints_across(const JointSetSpec& set, const Box& box)
{
  const Vec3 n = normal_from_dip(set.dip, set.dip_direction);
  double lo = 1e308, hi = -1e308;
  for (int corner = 0; corner < 8; ++corner)
  {
    const Vec3 p((corner & 1 ? box.hi : box.lo).x(), (corner & 2 ? box.hi : box.lo).y(),
                 (corner & 4 ? box.hi : box.lo).z());
    const double s = n.dot(p - set.origin);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
  const double count = (hi - lo) / set.spacing + 1.0;
  return set.count > 0 ? std::min(count, static_cast<double>(set.count)) : count;
}

void check_deformable_blocks(const Scene& scene, const BlockModel& model);

} // namespace

void check_model_size(const Scene& scene)
{
  // Planes in general position split space into 1 + e1 + e2 + e3 cells,
  // where e_k sums the products of k plane counts; parallel joints of one
  // set never meet, so only products across sets count.
  double e1 = 0.0, e2 = 0.0, e3 = 0.0, most = -1.0;
  std::size_t densest = 0;
  for (std::size_t i = 0; i < scene.joint_sets.size(); ++i)
  {
    const JointSetSpec& set = scene.joint_sets[i];
    Box box = scene.brick;
    if (set.limited)
    {
      box.lo = box.lo.cwiseMax(set.extent.lo);
      box.hi = box.hi.cwiseMin(set.extent.hi).cwiseMax(box.lo);
    }
    const double n = joints_across(set, box);
    e3 += e2 * n;
    e2 += e1 * n;
    e1 += n;
    if (!(n <= most))
    {
      most = n;
      densest = i;
    }
  }
  for (std::size_t j = 0; j < scene.joint_planes.size(); ++j)
  {
    e3 += e2;
    e2 += e1;
    e1 += 1.0;
  }
  const double blocks = 1.0 + e1 + e2 + e3;
  if (!(blocks <= max_blocks) && !scene.joint_sets.empty())
    throw scene_error(scene, scene.joint_set_sections[densest], "Spacing",
                      "the joint sets would cut the brick into about " + number(blocks) +
                          " blocks, more than the " + number(max_blocks) +
                          " talus builds (about 1 KB of memory each)",
                      "a spacing that leaves at most " + number(max_blocks) + " blocks");
  const double bytes =
      blocks * (scene.solver.steps > 0 ? bytes_per_running_block : bytes_per_built_block);
  const double room = available_memory();
  if (!(bytes <= room) && !scene.joint_sets.empty())
    throw scene_error(scene, scene.joint_set_sections[densest], "Spacing",
                      "the joint sets would cut the brick into about " + number(blocks) +
                          " blocks, which need about " + memory_text(bytes) +
                          " of memory, and this machine has " + memory_text(room) + " left",
                      "a spacing that leaves fewer blocks, or a machine with more memory");
}

namespace
{
/// The checks of check_built_model on stages: every group a stage names
/// holds blocks, every region it excavates holds rock, and a deformable
/// body alone (which has no blocks to remove or hold) is only excavated by
/// regions.
template <typename HasBlocks>
void check_stages(const Scene& scene, const ModelDigest& model, const BuildReport& report,
                  const HasBlocks& check_has_blocks)
{
  const bool body = !scene.deformable.groups.empty() && model.n_blocks() == 1;
  if (scene.strength_reduction.enabled && !scene.stages.empty())
    throw scene_error(scene, "Solver", "Mode",
                      "the factor of safety is searched for the model as built, and this scene "
                      "has stages",
                      "'static' or 'dynamic' with stages (a stage of its own may have 'Mode = "
                      "factor of safety'); 'factor of safety' without them");
  std::size_t k = 0;
  for (const StageSpec& stage : scene.stages)
  {
    if (body && stage.factor_of_safety)
      throw scene_error(scene, stage.section, "Mode",
                        "factor of safety is searched on blocks, and the scene is one "
                        "deformable body",
                        "static or dynamic for a body alone ('Solver / Mode = factor of "
                        "safety' searches it without stages)");
    if (stage.factor_of_safety && !scene.deformable.mesh_file.empty())
      throw scene_error(scene, stage.section, "Mode",
                        "factor of safety does not take a 'Mesh file'", "static or dynamic");
    const std::pair<const char*, const std::vector<std::string>*> lists[] = {
        {"Excavate groups", &stage.excavate_groups},
        {"Fix groups", &stage.fix_groups},
        {"Free groups", &stage.free_groups}};
    for (const auto& [entry, groups] : lists)
    {
      if (body && !groups->empty())
        throw scene_error(scene, stage.section, entry,
                          "the scene is one deformable body, with no blocks to remove or hold",
                          "an 'Excavation M' in the stage to remove zones, 'Boundary N' to hold "
                          "gridpoints");
      for (const std::string& g : *groups)
      {
        check_has_blocks(stage.section, entry, g);
        // Deformable blocks are held by their gridpoints, not as blocks.
        const bool deformable =
            std::find(scene.deformable.groups.begin(), scene.deformable.groups.end(), g) !=
            scene.deformable.groups.end();
        if (deformable && std::string(entry) != "Excavate groups")
          throw scene_error(scene, stage.section, entry,
                            "names group '" + g +
                                "', whose blocks are deformable: a stage holds "
                                "or lets go rigid blocks only",
                            "groups of rigid blocks; 'Boundary N' holds gridpoints of deformable "
                            "ones");
      }
    }
    for (const RockMaterialChange& c : stage.rock_materials)
      check_has_blocks(stage.section, "Rock materials", c.group);
    for (const GroupContactChange& c : stage.group_contacts)
    {
      check_has_blocks(stage.section, "Group contacts", c.a);
      check_has_blocks(stage.section, "Group contacts", c.b);
    }
    if (body && !stage.group_contacts.empty())
      throw scene_error(scene, stage.section, "Group contacts",
                        "the scene is one deformable body, without contacts",
                        "no 'Group contacts' for a body alone");
    if (body && !stage.joint_materials.empty())
      throw scene_error(scene, stage.section, "Joint materials",
                        "the scene is one deformable body, without joints",
                        "no 'Joint materials' in a scene of one body");
    // A body from a mesh file is not cut: its zones are checked once read.
    if (scene.deformable.mesh_file.empty())
      for (const ExcavationSpec& e : stage.excavations)
        if (!(k < report.stage_excavated_volume.size() && report.stage_excavated_volume[k++] > 0.0))
          throw scene_error(scene, e.section, "",
                            "removes no rock (the region lies outside the blocks)",
                            "a region that overlaps the model");
  }
}
} // namespace

void check_built_model(const Scene& scene, const ModelDigest& model, const BuildReport& report,
                       const BlockModel* whole)
{
  const auto cuts_nothing =
      [&](const std::string& section, const std::pair<unsigned long, unsigned long>& cuts)
  {
    if (cuts.first > 0)
      return;
    throw scene_error(scene, section, "",
                      cuts.second > 0 ? "cuts no block: its " + std::to_string(cuts.second) +
                                            " cuts would all leave pieces smaller than the "
                                            "'Minimum block volume' of subsection 'Model' (" +
                                            number(scene.cutting.minimum_volume) + " m^3)"
                                      : "cuts no block (its planes miss the blocks, or lie on "
                                        "faces that are already there)",
                      "joints that cross the model (see Origin, Dip, Dip direction and the "
                      "extent)");
  };
  for (std::size_t i = 0; i < report.joint_set_cuts.size(); ++i)
    cuts_nothing(scene.joint_set_sections[i], report.joint_set_cuts[i]);
  for (std::size_t i = 0; i < report.joint_cuts.size(); ++i)
    cuts_nothing(scene.joint_plane_sections[i], report.joint_cuts[i]);

  for (std::size_t e = 0; e < scene.excavations.size(); ++e)
    if (!(report.excavated_volume[e] > 0.0))
    {
      // A region thinner than the cutting tolerance cuts nothing either.
      const double tolerance =
          scene.cutting.relative_tolerance * (scene.brick.hi - scene.brick.lo).norm();
      if (std::cbrt(scene.excavations[e].region.volume) < 1e3 * tolerance)
        throw scene_error(scene, scene.excavations[e].section, "",
                          "removes no rock: the region is too small to cut (its volume is " +
                              number(scene.excavations[e].region.volume) +
                              " m^3, and planes closer than the cutting tolerance, about " +
                              number(tolerance) + " m here, count as one)",
                          "a region much larger than the cutting tolerance ('Cutting "
                          "tolerance' of subsection 'Model' times the block size)");
      throw scene_error(scene, scene.excavations[e].section, "",
                        "removes no rock (the region lies outside the blocks that are left)",
                        "a region that overlaps the model");
    }
  if (model.n_blocks() == 0)
    throw scene_error(scene, scene.excavations.empty() ? "Model" : scene.excavations.back().section,
                      "", "no block is left: the excavations remove the whole model",
                      "excavations that leave part of the brick");

  for (const GroupSpec& g : scene.groups)
    for (unsigned int b : g.blocks)
      if (b >= model.n_blocks())
        throw scene_error(scene, g.section, "Blocks",
                          "block " + std::to_string(b) + " does not exist (the model has " +
                              std::to_string(model.n_blocks()) + " blocks)",
                          "0 to " + std::to_string(model.n_blocks() - 1));
  for (unsigned int b : scene.solver.history_blocks)
    if (b >= model.n_blocks())
      throw scene_error(scene, "Solver", "History blocks",
                        "block " + std::to_string(b) + " does not exist (the model has " +
                            std::to_string(model.n_blocks()) + " blocks)",
                        "0 to " + std::to_string(model.n_blocks() - 1));

  // A group named by an entry must hold blocks, or the entry does nothing.
  const auto check_has_blocks =
      [&](const std::string& section, const std::string& entry, const std::string& group)
  {
    if (model.blocks_in(group) > 0)
      return;
    throw scene_error(scene, section, entry,
                      "the group '" + group +
                          "' holds no block (its region selects none, or "
                          "the cuts and excavations left none in it)",
                      "groups that hold blocks");
  };
  for (const std::string& g : scene.fixed_groups)
    check_has_blocks("Solver", "Fixed groups", g);
  check_stages(scene, model, report, check_has_blocks);
  for (std::size_t l = 0; l < scene.load_groups.size(); ++l)
  {
    check_has_blocks(scene.load_sections.at(l), "Group", scene.load_groups[l]);
    // An initial motion is given to rigid blocks; a deformable block's
    // gridpoints would start at rest whatever it says.
    const BlockLoad& load = scene.solver.loads.at(l);
    const std::vector<std::string>& d = scene.deformable.groups;
    if (std::find(d.begin(), d.end(), scene.load_groups[l]) != d.end() &&
        (load.initial_velocity != Vec3::Zero() || load.initial_spin != Vec3::Zero()))
      throw scene_error(scene, scene.load_sections[l],
                        load.initial_velocity != Vec3::Zero() ? "Initial velocity" : "Initial spin",
                        "is given to rigid blocks only, and group '" + scene.load_groups[l] +
                            "' is deformable (its gridpoints would start at rest)",
                        "0, 0, 0 for a deformable group; an initial motion for groups of rigid "
                        "blocks");
  }
  for (const StageSpec& stage : scene.stages)
    for (std::size_t l = 0; l < stage.boundaries.load_groups.size(); ++l)
      check_has_blocks(stage.boundaries.load_sections.at(l), "Group",
                       stage.boundaries.load_groups[l]);

  if (!scene.deformable.groups.empty())
  {
    if (whole == nullptr)
      throw std::logic_error("check_built_model: deformable blocks are checked on the whole model");
    check_deformable_blocks(scene, *whole);
  }
  // Every check passed: what is legal but surely not meant.
  for (const std::string& w : scene.warnings)
    std::printf("Warning: %s\n", w.c_str());
}

namespace
{

/// The blocks of the deformable groups.
std::vector<unsigned int> deformable_blocks(const Scene& scene, const BlockModel& model)
{
  std::vector<unsigned int> deformable;
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    if (std::find(scene.deformable.groups.begin(), scene.deformable.groups.end(),
                  model.group_names[model.group[b]]) != scene.deformable.groups.end())
      deformable.push_back(b);
  return deformable;
}

/// The largest side of block b's bounding box (m).
double block_extent(const BlockModel& model, unsigned int b)
{
  Box box{model.vertex[model.vertex_start[b]], model.vertex[model.vertex_start[b]]};
  for (unsigned int v = model.vertex_start[b]; v < model.vertex_start[b + 1]; ++v)
  {
    box.lo = box.lo.cwiseMin(model.vertex[v]);
    box.hi = box.hi.cwiseMax(model.vertex[v]);
  }
  return (box.hi - box.lo).maxCoeff();
}

/// The checks of check_built_model on deformable blocks.
void check_deformable_blocks(const Scene& scene, const BlockModel& model)
{
  const std::vector<unsigned int> deformable = deformable_blocks(scene, model);
  if (deformable.empty())
    throw scene_error(scene, "Deformable", "Groups", "no block of the model is in these groups",
                      "groups that hold blocks");
  if (scene.deformable.material.element == ZoneElement::hex_mixed &&
      scene.deformable.mesh_file.empty())
    for (unsigned int b : deformable)
    {
      Box box;
      if (!is_axis_aligned_box(model, b, box))
        throw scene_error(scene, "Deformable", "Element",
                          "hex-mixed needs every deformable block to be an axis-aligned brick, "
                          "and block " +
                              std::to_string(b) + " (" +
                              std::to_string(model.face_start[b + 1] - model.face_start[b]) +
                              " faces, centroid " + number(model.centroid[b].x()) + ", " +
                              number(model.centroid[b].y()) + ", " + number(model.centroid[b].z()) +
                              " m) is not one",
                          "tet4 or tet10 for blocks of other shapes");
    }
  {
    // A rock so soft that its own weight would strain a block by more than
    // a half (rho g L / E, L its height or width) collapses: the zones
    // invert within a few steps and the run can only diverge.
    for (unsigned int b : deformable)
    {
      const double extent = block_extent(model, b);
      const std::string& group = model.group_names[model.group[b]];
      const RockMaterialSpec* rock = scene.rock_material_of(group);
      const double weight = scene.density_of(group) * scene.solver.gravity.norm(); // N/m^3
      const double E = (rock != nullptr ? rock->zone : scene.deformable.material).young();
      const double strain = weight * extent / E;
      if (strain > 0.5)
        throw scene_error(scene, rock != nullptr ? rock->section : "Deformable", "Young's modulus",
                          "makes blocks of group '" + group + "' so soft (E = " + number(E) +
                              " Pa) that their own weight would strain them by about " +
                              number(strain) + " (density x gravity x " + number(extent) +
                              " m / E): they would collapse",
                          "a Young's modulus of at least " + number(2.0 * weight * extent) +
                              " Pa for these blocks (own-weight strain at most 0.5)");
    }
  }
  if (!scene.deformable.mesh_file.empty())
  {
    if (model.n_blocks() != 1)
      throw scene_error(scene, "Deformable", "Mesh file",
                        "a mesh file is the body of a scene of one block, and this scene has " +
                            std::to_string(model.n_blocks()) + " blocks",
                        "a mesh file only for a scene without joints or excavations");
    return; // the file's zones are used, not the edge length
  }
  double largest_extent = 0.0;
  for (unsigned int b : deformable)
    largest_extent = std::max(largest_extent, block_extent(model, b));
  const EdgeLengthField& field = scene.deformable.edge_length;
  const double edge = field.smallest();
  if (!field.graded() && edge > largest_extent)
    throw scene_error(scene, "Deformable", "Edge length",
                      number(edge) +
                          " m is larger than every deformable block (the largest spans " +
                          number(largest_extent) + " m)",
                      "a number > 0 and at most " + number(largest_extent) + " (m)");
  const ZoneEstimate estimate = estimate_zones(scene, model);
  const double zones = estimate.zones;
  const char* entry = field.graded() ? "Fine edge length" : "Edge length";
  if (!(zones <= max_zones))
    throw scene_error(scene, "Deformable", entry,
                      number(edge) + " m would make " + number(zones) + " zones, more than the " +
                          number(max_zones) +
                          " talus meshes (about 620 bytes of memory each while meshing)",
                      "an edge length that makes at most " + number(max_zones) + " zones");
  const double bytes = estimate.bytes;
  const double room = available_memory();
  if (!(bytes <= room))
    throw scene_error(scene, "Deformable", entry,
                      number(edge) + " m would make about " + number(zones) +
                          " zones, which need about " + memory_text(bytes) +
                          " of memory to mesh, and this machine has " + memory_text(room) + " left",
                      "a larger edge length, fewer deformable groups, or a machine with more "
                      "memory");
}

} // namespace

ZoneEstimate estimate_zones(const Scene& scene, const BlockModel& model)
{
  ZoneEstimate e;
  if (!scene.deformable.mesh_file.empty())
    return e;
  const std::vector<unsigned int> deformable = deformable_blocks(scene, model);
  e.blocks = deformable.size();
  e.quadratic = scene.deformable.material.element == ZoneElement::tet10;
  // Hexahedral zones count as their ten tetrahedra (two overlays of five).
  e.zones = count_zones(model, deformable, scene.deformable.edge_length) *
            (scene.deformable.material.element == ZoneElement::hex_mixed ? 2.0 : 1.0);
  e.bytes = e.zones * bytes_per_zone * (e.quadratic ? 4.0 : 1.0);
  return e;
}

namespace
{
/// Whether part of a rigid block's face lies in a face load's region;
/// `k`: the load's place among the scene's own and then those of each
/// stage that changes boundaries (ModelDigest::rigid_face_in).
using RigidFaceIn = std::function<bool(std::size_t k, const ConvexRegion& region)>;

/// `first`: the place of the set's first face load among the scene's.
void check_selections(const Scene& scene, const RigidFaceIn& rigid_face_in, const TetMesh& mesh,
                      const BoundarySet& set, std::size_t first);

void check_all_selections(const Scene& scene, const RigidFaceIn& rigid_face_in, const TetMesh& mesh)
{
  BoundarySet file;
  file.gridpoint_conditions = scene.gridpoint_conditions;
  file.gridpoint_condition_sections = scene.gridpoint_condition_sections;
  file.face_pressures = scene.face_pressures;
  file.face_pressure_sections = scene.face_pressure_sections;
  check_selections(scene, rigid_face_in, mesh, file, 0);
  std::size_t first = file.face_pressures.size();
  for (const StageSpec& stage : scene.stages)
    if (stage.changes_boundaries)
    {
      check_selections(scene, rigid_face_in, mesh, stage.boundaries, first);
      first += stage.boundaries.face_pressures.size();
    }
}

void check_selections(const Scene& scene, const RigidFaceIn& rigid_face_in, const TetMesh& mesh,
                      const BoundarySet& set, std::size_t first)
{
  // As the solvers select: gridpoints and zone face centroids by their
  // initial positions, the parts of rigid blocks' faces in the box.
  const auto holds = [](const ConvexRegion& region, const double* p)
  { return region.holds(Vec3(p[0], p[1], p[2])); };
  for (std::size_t i = 0; i < set.gridpoint_conditions.size(); ++i)
  {
    const ConvexRegion& box = set.gridpoint_conditions[i].region;
    bool any = false;
    for (unsigned int g = 0; g < mesh.n_gridpoints() && !any; ++g)
      any = holds(box, &mesh.position[3 * g]);
    if (!any)
      throw scene_error(
          scene, set.gridpoint_condition_sections[i], "",
          mesh.n_gridpoints() == 0
              ? "selects nothing: fixed, velocity and load boundaries act on the gridpoints of "
                "deformable blocks, and this scene has none"
          : box.is_box ? "selects nothing: no gridpoint of a deformable block lies in its box "
                         "('Corner min' to 'Corner max')"
                       : "selects nothing: no gridpoint of a deformable block lies in its region "
                         "('Shape' and its entries)",
          "a box around gridpoints of deformable blocks (rigid blocks are held with 'Fixed "
          "groups' of subsection 'Solver', or moved and loaded with 'Load N')");
  }
  const auto face_in = [&](const ConvexRegion& box, const std::array<unsigned int, 3>& face)
  {
    double c[3] = {0, 0, 0};
    for (unsigned int g : face)
      for (int d = 0; d < 3; ++d)
        c[d] += mesh.position[3 * g + d] / 3.0;
    return holds(box, c);
  };
  for (std::size_t i = 0; i < set.face_pressures.size(); ++i)
  {
    const ConvexRegion& box = set.face_pressures[i].region;
    const bool quiet = set.face_pressures[i].quiet; // zone faces only
    bool any = !quiet && rigid_face_in(first + i, box);
    for (const auto& face : mesh.face_gridpoint)
      any = any || face_in(box, face);
    for (const auto& face : mesh.second_overlay_face_gridpoint)
      any = any || face_in(box, face);
    if (!any && quiet)
      throw scene_error(scene, set.face_pressure_sections[i], "",
                        "selects nothing: a quiet boundary acts on the boundary faces of "
                        "deformable blocks' zones, and none has its centroid in its region",
                        "a region around zone faces of deformable blocks (a thin box around a "
                        "plane face, or a half-space beyond it)");
    if (!any)
      throw scene_error(scene, set.face_pressure_sections[i], "",
                        box.is_box ? "selects nothing: no part of a rigid block's face lies in "
                                     "its box ('Corner min' to 'Corner max'), and no boundary "
                                     "face of a deformable block's zones has its centroid in it"
                                   : "selects nothing: no rigid block's face lies wholly in its "
                                     "region ('Shape' and its entries), and no boundary face of "
                                     "a deformable block's zones has its centroid in it",
                        "a box around the faces to load (it may be thin, around a plane face), "
                        "or a region of another shape that holds whole faces");
  }
}

} // namespace

/// The rigid blocks of `model`: those not in a deformable group.
std::vector<char> rigid_blocks(const Scene& scene, const BlockModel& model)
{
  std::vector<char> rigid(model.n_blocks(), 1);
  for (unsigned int b = 0; b < model.n_blocks(); ++b)
    for (const std::string& g : scene.deformable.groups)
      if (model.group_names[model.group[b]] == g)
        rigid[b] = 0;
  return rigid;
}

void check_boundary_selections(const Scene& scene, const BlockModel& model, const TetMesh& mesh)
{
  const std::vector<char> rigid = rigid_blocks(scene, model);
  check_all_selections(
      scene,
      [&](std::size_t, const ConvexRegion& box)
      { return !face_patches_in(model, rigid, box).empty(); },
      mesh);
}

void check_boundary_selections(const Scene& scene, const BlockModel& model, const TetMesh& mesh,
                               const BoundarySet& set)
{
  const std::vector<char> rigid = rigid_blocks(scene, model);
  check_selections(
      scene,
      [&](std::size_t, const ConvexRegion& box)
      { return !face_patches_in(model, rigid, box).empty(); },
      mesh, set, 0);
}

void check_boundary_selections(const Scene& scene, const ModelDigest& model, const TetMesh& mesh)
{
  check_all_selections(
      scene, [&](std::size_t k, const ConvexRegion&) { return model.rigid_face_in(k); }, mesh);
}

} // namespace talus
