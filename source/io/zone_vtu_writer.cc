#include <talus/io/file_output.h>
#include <talus/io/zone_vtu_writer.h>
#include <talus/zone/hex_mixed.h>
#include <talus/zone/tet10_mesh.h>
#include <talus/zone/zone_triangulation.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <Eigen/Eigenvalues>

#include <ostream>
#include <stdexcept>

namespace talus
{

void principal_stresses(const double* s, double* p)
{
  Eigen::Matrix3d m;
  m << s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2];
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(m, Eigen::EigenvaluesOnly);
  for (int d = 0; d < 3; ++d)
    p[d] = eigen.eigenvalues()[d]; // ascending
}

namespace
{
using Interpretation = dealii::DataComponentInterpretation::DataComponentInterpretation;

/// Components a field takes in the output: a symmetric tensor of 6 is
/// written as all 9 entries, so that ParaView sees a tensor.
unsigned int output_components(const ZoneField& f)
{
  return f.components == 6 ? 9 : f.components;
}

/// Which stored component (of 6: xx yy zz xy yz zx) is tensor entry (i, j),
/// row-major.
constexpr unsigned int voigt_of[9] = {0, 3, 5, 3, 1, 4, 5, 4, 2};
} // namespace

/// The DoF layout of one field set: a linear field per gridpoint component
/// and a constant one per zone component, in one FESystem, so that DataOut
/// writes them all from one vector.
struct ZoneWriter::Data
{
  std::vector<std::array<unsigned int, 4>> cells; ///< the shown tetrahedra
  std::vector<unsigned int> cell_block;
  std::unique_ptr<dealii::Triangulation<3>> tria;
  dealii::MappingFE<3> mapping{dealii::FE_SimplexP<3>(1)};
  std::unique_ptr<dealii::FESystem<3>> fe;
  dealii::DoFHandler<3> dofs;
  std::vector<unsigned int> point_components, zone_components; ///< as given
  /// dof_of_point[c][g]: the DoF of point component c at gridpoint g;
  /// dof_of_zone[c][z]: of output zone component c in zone z.
  std::vector<std::vector<dealii::types::global_dof_index>> dof_of_point, dof_of_zone;
};

std::vector<std::array<unsigned int, 4>> shown_tetrahedra(const TetMesh& mesh)
{
  if (mesh.quadratic())
  {
    std::vector<std::array<unsigned int, 4>> cells;
    cells.reserve(8 * mesh.n_zones());
    for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    {
      unsigned int node[10];
      for (int k = 0; k < 4; ++k)
        node[k] = mesh.zone_gridpoint[z][k];
      for (int k = 0; k < 6; ++k)
        node[4 + k] = mesh.zone_edge_gridpoint[z][k];
      for (const auto& sub : tet10_subcell)
        cells.push_back({{node[sub[0]], node[sub[1]], node[sub[2]], node[sub[3]]}});
    }
    return cells;
  }
  const std::vector<char> in_hex = zones_in_hexes(mesh);
  std::vector<std::array<unsigned int, 4>> cells;
  cells.reserve(mesh.n_zones());
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (!in_hex[z])
      cells.push_back(mesh.zone_gridpoint[z]);
  // Hexahedra after the plain zones: the first five tetrahedra of each.
  for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
    for (unsigned int k = 0; k < TetMesh::tets_per_hex / 2; ++k)
      cells.push_back(mesh.zone_gridpoint[mesh.hex_first_zone[h] + k]);
  return cells;
}

void shown_zone_values(const TetMesh& mesh, const std::vector<double>& x,
                       const std::vector<double>& stress, const std::vector<unsigned char>& state,
                       std::vector<double>& cell_stress, std::vector<unsigned char>& cell_state)
{
  const std::vector<char> in_hex = zones_in_hexes(mesh);
  cell_stress.clear();
  cell_state.clear();
  for (unsigned int z = 0; z < mesh.n_zones(); ++z)
    if (!in_hex[z])
    {
      cell_stress.insert(cell_stress.end(), &stress[6 * z], &stress[6 * z + 6]);
      cell_state.push_back(state[z]);
    }
  const std::vector<double> hex_stress = hex_zone_stress(mesh, x, stress);
  for (unsigned int h = 0; h < mesh.n_hexes(); ++h)
  {
    unsigned char flags = 0;
    for (unsigned int k = 0; k < TetMesh::tets_per_hex; ++k)
      flags |= state[mesh.hex_first_zone[h] + k];
    for (unsigned int k = 0; k < TetMesh::tets_per_hex / 2; ++k)
    {
      cell_stress.insert(cell_stress.end(), &hex_stress[6 * h], &hex_stress[6 * h + 6]);
      cell_state.push_back(flags);
    }
  }
}

ZoneWriter::ZoneWriter(const TetMesh& mesh) : mesh_(mesh) {}

ZoneWriter::~ZoneWriter() = default;

void ZoneWriter::write(const std::string& path, const std::vector<double>& positions,
                       const std::vector<ZoneField>& point_fields,
                       const std::vector<ZoneField>& zone_fields, double time)
{
  if (!data_)
  {
    data_ = std::make_unique<Data>();
    data_->cells = shown_tetrahedra(mesh_);
    const std::vector<char> in_hex = zones_in_hexes(mesh_);
    for (unsigned int z = 0; z < mesh_.n_zones(); ++z)
      if (!in_hex[z])
        data_->cell_block.insert(data_->cell_block.end(), mesh_.quadratic() ? 8 : 1,
                                 mesh_.zone_block[z]);
    for (unsigned int h = 0; h < mesh_.n_hexes(); ++h)
      data_->cell_block.insert(data_->cell_block.end(), TetMesh::tets_per_hex / 2,
                               mesh_.zone_block[mesh_.hex_first_zone[h]]);
    data_->tria = build_zone_triangulation(mesh_.position, data_->cells, data_->cell_block);
    unsigned int n_point = 0, n_zone = 0;
    for (const ZoneField& f : point_fields)
    {
      data_->point_components.push_back(f.components);
      n_point += f.components;
    }
    for (const ZoneField& f : zone_fields)
    {
      data_->zone_components.push_back(f.components);
      n_zone += output_components(f);
    }
    if (n_point > 0 && n_zone > 0)
      data_->fe = std::make_unique<dealii::FESystem<3>>(dealii::FE_SimplexP<3>(1), n_point,
                                                        dealii::FE_SimplexDGP<3>(0), n_zone);
    else if (n_point > 0)
      data_->fe = std::make_unique<dealii::FESystem<3>>(dealii::FE_SimplexP<3>(1), n_point);
    else
      data_->fe = std::make_unique<dealii::FESystem<3>>(dealii::FE_SimplexDGP<3>(0), n_zone);
    data_->dofs.reinit(*data_->tria);
    data_->dofs.distribute_dofs(*data_->fe);
    data_->dof_of_point.assign(n_point,
                               std::vector<dealii::types::global_dof_index>(mesh_.n_gridpoints()));
    data_->dof_of_zone.assign(n_zone,
                              std::vector<dealii::types::global_dof_index>(data_->cells.size()));
    std::vector<dealii::types::global_dof_index> local(data_->fe->n_dofs_per_cell());
    for (const auto& cell : data_->dofs.active_cell_iterators())
    {
      cell->get_dof_indices(local);
      for (unsigned int i = 0; i < local.size(); ++i)
      {
        // The linear element's DoF k sits at vertex k of the cell.
        const auto [component, within] = data_->fe->system_to_component_index(i);
        if (component < n_point)
          data_->dof_of_point[component][cell->vertex_index(within)] = local[i];
        else
          data_->dof_of_zone[component - n_point][cell->active_cell_index()] = local[i];
      }
    }
  }
  else
  {
    bool same = data_->point_components.size() == point_fields.size() &&
                data_->zone_components.size() == zone_fields.size();
    for (std::size_t k = 0; same && k < point_fields.size(); ++k)
      same = data_->point_components[k] == point_fields[k].components;
    for (std::size_t k = 0; same && k < zone_fields.size(); ++k)
      same = data_->zone_components[k] == zone_fields[k].components;
    if (!same)
      throw std::logic_error("ZoneWriter: the fields changed between frames");
  }

  // The cells follow the gridpoints: the triangulation's vertices are moved
  // to the current positions for this frame.
  for (const auto& cell : data_->tria->active_cell_iterators())
    for (unsigned int i = 0; i < 4; ++i)
    {
      const unsigned int g = cell->vertex_index(i);
      cell->vertex(i) =
          dealii::Point<3>(positions[3 * g], positions[3 * g + 1], positions[3 * g + 2]);
    }

  dealii::Vector<double> values(data_->dofs.n_dofs());
  std::vector<std::string> names;
  std::vector<Interpretation> interpretation;
  unsigned int c = 0;
  for (const ZoneField& f : point_fields)
    for (unsigned int k = 0; k < f.components; ++k, ++c)
    {
      for (unsigned int g = 0; g < mesh_.n_gridpoints(); ++g)
        values[data_->dof_of_point[c][g]] = f.values[f.components * g + k];
      names.push_back(f.name);
      interpretation.push_back(
          f.components == 1 ? dealii::DataComponentInterpretation::component_is_scalar
                            : dealii::DataComponentInterpretation::component_is_part_of_vector);
    }
  unsigned int zc = 0;
  for (const ZoneField& f : zone_fields)
  {
    const unsigned int n = output_components(f);
    for (unsigned int k = 0; k < n; ++k, ++zc)
    {
      const unsigned int stored = f.components == 6 ? voigt_of[k] : k;
      for (std::size_t z = 0; z < data_->cells.size(); ++z)
        values[data_->dof_of_zone[zc][z]] = f.values[f.components * z + stored];
      names.push_back(f.name);
      interpretation.push_back(
          n == 1   ? dealii::DataComponentInterpretation::component_is_scalar
          : n == 9 ? dealii::DataComponentInterpretation::component_is_part_of_tensor
                   : dealii::DataComponentInterpretation::component_is_part_of_vector);
    }
  }
  dealii::Vector<double> block_id(data_->cells.size());
  for (std::size_t z = 0; z < data_->cells.size(); ++z)
    block_id[z] = data_->cell_block[z];

  dealii::DataOut<3> out;
  out.attach_dof_handler(data_->dofs);
  out.add_data_vector(values, names, dealii::DataOut<3>::type_dof_data, interpretation);
  out.add_data_vector(block_id, "block_id", dealii::DataOut<3>::type_cell_data);
  out.build_patches(data_->mapping);
  dealii::DataOutBase::VtkFlags flags(time);
  flags.print_date_and_time = false; // same state, same file (restart tests compare bytes)
  out.set_flags(flags);
  write_file_atomically(path, [&](std::ostream& stream) { out.write_vtu(stream); });
}

} // namespace talus
