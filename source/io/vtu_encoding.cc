#include <talus/io/vtu_encoding.h>

#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <future>
#include <stdexcept>
#include <thread>

namespace talus
{

void write_vtu_file_start(std::ostream& out, VtuEncoding encoding)
{
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (encoding == VtuEncoding::binary ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n";
}

void append_base64(const unsigned char* bytes, std::size_t size, std::string& text)
{
  static constexpr char digit[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::size_t start = text.size();
  text.resize(start + 4 * ((size + 2) / 3));
  char* to = &text[start];
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3, to += 4)
  {
    const std::uint32_t word = (std::uint32_t(bytes[i]) << 16) |
                               (std::uint32_t(bytes[i + 1]) << 8) | std::uint32_t(bytes[i + 2]);
    to[0] = digit[word >> 18];
    to[1] = digit[(word >> 12) & 63];
    to[2] = digit[(word >> 6) & 63];
    to[3] = digit[word & 63];
  }
  if (i < size) // one or two bytes left: padded with '='
  {
    const std::uint32_t word =
        (std::uint32_t(bytes[i]) << 16) | (i + 1 < size ? std::uint32_t(bytes[i + 1]) << 8 : 0);
    to[0] = digit[word >> 18];
    to[1] = digit[(word >> 12) & 63];
    to[2] = i + 1 < size ? digit[(word >> 6) & 63] : '=';
    to[3] = '=';
  }
}

unsigned int vtu_compression_lanes()
{
  static const unsigned int lanes = std::clamp(std::thread::hardware_concurrency(), 1u, 4u);
  return lanes;
}

namespace
{
/// A zlib stream reset for each block (each block a zlib stream of its
/// own, as VTK reads them) at zlib's fastest level, with matching or with
/// Huffman coding alone.
struct BlockStream
{
  z_stream stream{};
  explicit BlockStream(bool huffman_only)
  {
    if (deflateInit2(&stream, Z_BEST_SPEED, Z_DEFLATED, 15, 8,
                     huffman_only ? Z_HUFFMAN_ONLY : Z_DEFAULT_STRATEGY) != Z_OK)
      throw std::runtime_error("VTU output: zlib cannot start");
  }
  ~BlockStream() { deflateEnd(&stream); }
  void compress(const void* data, std::size_t bytes, std::string& packed)
  {
    if (deflateReset(&stream) != Z_OK)
      throw std::runtime_error("VTU output: zlib failed");
    packed.resize(deflateBound(&stream, bytes));
    stream.next_in = static_cast<Bytef*>(const_cast<void*>(data));
    stream.avail_in = static_cast<uInt>(bytes);
    stream.next_out = reinterpret_cast<Bytef*>(&packed[0]);
    stream.avail_out = static_cast<uInt>(packed.size());
    if (deflate(&stream, Z_FINISH) != Z_STREAM_END)
      throw std::runtime_error("VTU output: zlib failed");
    packed.resize(stream.total_out);
  }
};
} // namespace

/// One lane: its two streams and the block it compressed.
struct VtuArrayEncoder::Deflater
{
  BlockStream matching{false}, huffman{true};
  std::string packed;
};

bool VtuArrayEncoder::huffman_only(std::size_t block) const
{
  // zlib's matching shrinks the integer arrays 3 to 200 times, and smooth
  // or uniform fields 10 to 200 times (a run's early frames), but noisy
  // floating-point fields only to about 0.55, where Huffman coding alone
  // reaches about 0.75 at under two thirds of the time (benchmark_vtu_write:
  // the difference between a million zones per second and less). So a
  // floating-point array's blocks take Huffman coding while matching gets
  // less than 0.35 off the block four before, and matching again once
  // Huffman coding takes more than half off it. Looking four blocks back
  // (not one) lets up to four lanes work at once with the same bytes
  // whatever their number.
  if (!floating_point_ || block < 4)
    return false;
  const double ratio = block_ratio_[block - 4];
  return block_huffman_[block - 4] ? ratio >= 0.5 : ratio > 0.35;
}

VtuArrayEncoder::VtuArrayEncoder(std::ostream& out, VtuEncoding encoding, const char* type,
                                 const std::string& name, unsigned int components,
                                 std::size_t block_bytes)
    : out_(out), encoding_(encoding), floating_point_(type[0] == 'F') // Float32, Float64
{
  out_ << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\""
       << components << "\" format=\"" << (encoding == VtuEncoding::binary ? "binary" : "ascii")
       << "\">\n";
  if (encoding == VtuEncoding::binary)
    header_ = {0, block_bytes, 0};
}

VtuArrayEncoder::~VtuArrayEncoder() = default;

void VtuArrayEncoder::add_blocks(const void* const* data, const std::size_t* bytes, unsigned int n)
{
  while (deflaters_.size() < n)
    deflaters_.push_back(std::make_unique<Deflater>());
  // Blocks 1.. on threads of their own, block 0 here; the same bytes as one
  // after the other (restarted runs compare files byte for byte).
  const std::size_t first = header_[0];
  const auto compress = [&](unsigned int k)
  {
    Deflater& d = *deflaters_[k];
    (huffman_only(first + k) ? d.huffman : d.matching).compress(data[k], bytes[k], d.packed);
  };
  std::vector<std::future<void>> others;
  for (unsigned int k = 1; k < n; ++k)
    others.push_back(std::async(std::launch::async, compress, k));
  compress(0);
  for (std::future<void>& f : others)
    f.get(); // passes on an exception
  for (unsigned int k = 0; k < n; ++k)
  {
    block_huffman_.push_back(huffman_only(first + k));
    block_ratio_.push_back(static_cast<float>(deflaters_[k]->packed.size()) /
                           static_cast<float>(bytes[k]));
    packed_ += deflaters_[k]->packed;
    ++header_[0];
    header_.push_back(deflaters_[k]->packed.size());
    // The last block's size; 0 when it is a full one (VTK's convention).
    header_[2] = bytes[k] == header_[1] ? 0 : bytes[k];
  }
}

void VtuArrayEncoder::append_text(double value)
{
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  text_.append(buffer, end);
  text_.push_back(++column_ % 12 == 0 ? '\n' : ' ');
}

void VtuArrayEncoder::append_text(float value)
{
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  text_.append(buffer, end);
  text_.push_back(++column_ % 12 == 0 ? '\n' : ' ');
}

void VtuArrayEncoder::append_text(std::int64_t value)
{
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
  text_.append(buffer, end);
  text_.push_back(++column_ % 12 == 0 ? '\n' : ' ');
}

void VtuArrayEncoder::flush_text()
{
  out_.write(text_.data(), static_cast<std::streamsize>(text_.size()));
  text_.clear();
}

void VtuArrayEncoder::finish()
{
  if (encoding_ == VtuEncoding::binary)
  {
    // The header, then the blocks, each base64 on its own (VTK reads the
    // header first to find the blocks).
    append_base64(reinterpret_cast<const unsigned char*>(header_.data()),
                  header_.size() * sizeof(std::uint64_t), text_);
    flush_text();
    constexpr std::size_t piece = 3 * (1 << 14); // whole groups of 3 bytes
    const auto* bytes = reinterpret_cast<const unsigned char*>(packed_.data());
    for (std::size_t at = 0; at < packed_.size(); at += piece)
    {
      append_base64(bytes + at, std::min(piece, packed_.size() - at), text_);
      flush_text();
    }
    std::string().swap(packed_);
  }
  else
    flush_text();
  out_ << "\n        </DataArray>\n";
}

} // namespace talus
