#pragma once

// Shared by the tests that build a model in two ways and compare them: two
// block models, or two arrays, equal bit for bit.

#include <talus/model/block_model.h>

#include <cstring>
#include <vector>

namespace talus_test
{

template <typename T>
bool same_array_bits(const std::vector<T>& a, const std::vector<T>& b)
{
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

/// Every array of two models equal, bit for bit: vertices, faces, face
/// origins, mass properties, groups.
inline bool same_model(const talus::BlockModel& a, const talus::BlockModel& b)
{
  return same_array_bits(a.vertex, b.vertex) && same_array_bits(a.vertex_start, b.vertex_start) &&
         same_array_bits(a.face_vertex, b.face_vertex) &&
         same_array_bits(a.face_loop_start, b.face_loop_start) &&
         same_array_bits(a.face_normal, b.face_normal) &&
         same_array_bits(a.face_origin, b.face_origin) &&
         same_array_bits(a.face_start, b.face_start) && same_array_bits(a.volume, b.volume) &&
         same_array_bits(a.centroid, b.centroid) && same_array_bits(a.inertia, b.inertia) &&
         same_array_bits(a.group, b.group) && a.group_names == b.group_names;
}

} // namespace talus_test
