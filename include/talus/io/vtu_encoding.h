#pragma once

#include <talus/base/output_format.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <ostream>
#include <string>
#include <type_traits>
#include <vector>

namespace talus
{

/// The VTK type name of a value type.
template <typename T>
constexpr const char* vtk_type_name();
template <>
constexpr const char* vtk_type_name<double>()
{
  return "Float64";
}
template <>
constexpr const char* vtk_type_name<float>()
{
  return "Float32";
}
template <>
constexpr const char* vtk_type_name<std::int64_t>()
{
  return "Int64";
}
template <>
constexpr const char* vtk_type_name<std::int32_t>()
{
  return "Int32";
}
template <>
constexpr const char* vtk_type_name<std::uint8_t>()
{
  return "UInt8";
}

/// Writes the XML declaration and the opening VTKFile element of an
/// unstructured grid: little endian, UInt64 headers, and with `binary` the
/// zlib compressor.
void write_vtu_file_start(std::ostream& out, VtuEncoding encoding);

/// The uncompressed size of one block of a binary data array (bytes, less
/// what makes it whole tuples): blocks are filled, compressed and dropped
/// in turn, so that writing an array holds a block per lane plus the
/// array's compressed bytes.
inline constexpr std::size_t vtu_block_bytes = std::size_t(1) << 16;

/// How many blocks are compressed at once, each on a thread of its own:
/// the machine's cores, at most 4.
unsigned int vtu_compression_lanes();

/// One DataArray element being written, the values given block by block
/// (see write_data_array, which drives it).
class VtuArrayEncoder
{
public:
  VtuArrayEncoder(std::ostream& out, VtuEncoding encoding, const char* type,
                  const std::string& name, unsigned int components, std::size_t block_bytes);
  ~VtuArrayEncoder();
  /// Binary: compresses `n` blocks as the next ones, at the same time on up
  /// to vtu_compression_lanes() threads (every block but the array's last
  /// of `block_bytes`).
  void add_blocks(const void* const* data, const std::size_t* bytes, unsigned int n);
  /// ASCII: appends values as text, a line per 12.
  template <typename T>
  void add_text(const T* values, std::size_t count);
  /// Writes what is held (binary: the header and the compressed blocks, in
  /// base64) and closes the element.
  void finish();

private:
  void append_text(double value);
  void append_text(float value);
  void append_text(std::int64_t value);
  void flush_text();

  std::ostream& out_;
  VtuEncoding encoding_;
  // Binary: header words (blocks, block size, last block size, compressed
  // sizes) and the compressed blocks one after the other.
  std::vector<std::uint64_t> header_;
  std::string packed_;
  struct Deflater; ///< zlib's streams and their output: one per lane
  std::vector<std::unique_ptr<Deflater>> deflaters_;
  /// Binary: how each block was compressed and its compressed size over
  /// its size, which choose how the blocks four later are compressed.
  bool huffman_only(std::size_t block) const;
  bool floating_point_ = false;
  std::vector<char> block_huffman_;
  std::vector<float> block_ratio_;
  // ASCII: text waiting to be written, values on the current line.
  std::string text_;
  unsigned int column_ = 0;
};

template <typename T>
void VtuArrayEncoder::add_text(const T* values, std::size_t count)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    if constexpr (std::is_floating_point_v<T>)
      append_text(values[i]);
    else
      append_text(static_cast<std::int64_t>(values[i]));
    if (text_.size() > vtu_block_bytes)
      flush_text();
  }
}

/// Writes a DataArray element of `n_tuples` tuples of `components` values
/// of type T (double, float, std::int64_t, std::int32_t, std::uint8_t).
/// `fill(first, count, values)` puts tuples [first, first + count) into
/// `values` (count * components of them); it is called for consecutive
/// ranges of a block's size, so that nothing the size of the array is made.
template <typename T, typename Fill>
void write_data_array(std::ostream& out, VtuEncoding encoding, const std::string& name,
                      unsigned int components, std::size_t n_tuples, Fill fill)
{
  const std::size_t per_block =
      std::max<std::size_t>(1, vtu_block_bytes / (sizeof(T) * components));
  VtuArrayEncoder encoder(out, encoding, vtk_type_name<T>(), name, components,
                          per_block * components * sizeof(T));
  // Binary: as many blocks filled at a time as are compressed at once.
  const unsigned int lanes = encoding == VtuEncoding::binary ? vtu_compression_lanes() : 1;
  std::vector<std::vector<T>> values(lanes, std::vector<T>(per_block * components));
  std::vector<const void*> data(lanes);
  std::vector<std::size_t> bytes(lanes);
  for (std::size_t first = 0; first < n_tuples;)
  {
    unsigned int n = 0;
    for (; n < lanes && first < n_tuples; ++n, first += per_block)
    {
      const std::size_t count = std::min(per_block, n_tuples - first);
      fill(first, count, values[n].data());
      data[n] = values[n].data();
      bytes[n] = count * components * sizeof(T);
    }
    if (encoding == VtuEncoding::binary)
      encoder.add_blocks(data.data(), bytes.data(), n);
    else
      encoder.add_text(values[0].data(), bytes[0] / sizeof(T));
  }
  encoder.finish();
}

/// The same from values in memory (components per tuple, converted to T).
template <typename T, typename Source>
void write_data_array(std::ostream& out, VtuEncoding encoding, const std::string& name,
                      unsigned int components, const std::vector<Source>& source)
{
  write_data_array<T>(out, encoding, name, components, source.size() / components,
                      [&](std::size_t first, std::size_t count, T* values)
                      {
                        const Source* from = source.data() + first * components;
                        for (std::size_t i = 0; i < count * components; ++i)
                          values[i] = static_cast<T>(from[i]);
                      });
}

/// Base64 of `bytes` bytes (with '=' padding), appended to `text`.
void append_base64(const unsigned char* bytes, std::size_t size, std::string& text);

} // namespace talus
