#pragma once

#include <talus/zone/lattice_block_mesher.h>

#include <mpi.h>

#include <vector>

namespace talus
{

/// Meshes the given convex blocks as mesh_convex_blocks_with does, with the
/// work shared among the ranks of `comm`: each block is meshed by one rank,
/// and every rank then receives every block's tetrahedra. The meshers
/// treat each block on its own (gmsh one block per model, the lattice
/// mesher per block), so the result is the one-rank result, bit for bit.
///
/// The blocks are dealt out by `expected_zones` (one number per block of
/// `which`: count_zones), largest first, each to the rank with the least
/// so far; a rank meshes its blocks in the order of `which`.
///
/// Every rank of `comm` must call it with the same arguments. When a block
/// cannot be meshed, every rank throws the InputError that one rank would
/// have thrown (the first such block in the order of `which`), so that no
/// rank is left waiting in a collective call. With one rank in `comm` it is
/// mesh_convex_blocks_with.
std::vector<BlockTetrahedra>
mesh_convex_blocks_on_ranks(const BlockModel& blocks, const std::vector<unsigned int>& which,
                            const EdgeLengthAt& edge_length, ConvexMesher mesher,
                            const std::vector<double>& expected_zones, MPI_Comm comm);

/// Which rank of `ranks` meshes each block in mesh_convex_blocks_on_ranks.
std::vector<int> meshing_ranks(const std::vector<double>& expected_zones, int ranks);

} // namespace talus
